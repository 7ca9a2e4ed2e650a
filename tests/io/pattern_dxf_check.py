"""Reads a pattern DXF with ezdxf and prints what it found as JSON (for pattern_dxf_test).

Usage: /usr/bin/python3 pattern_dxf_check.py FILE.dxf
Output: {"dxfversion", "insunits", "measurement", "blocks": {name: {"cut": [...],
"sew": [...], "cut_closed", "sew_closed", "notches": [[x1, y1, x2, y2], ...],
"grain": [...], "texts": [...], "other_layers": [...]}}, "inserts": [[name, x, y], ...]}
where "cut"/"sew" hold the outline length (mm) and vertex count of each POLYLINE on
layer 1 / 14.
"""
import json
import math
import sys

import ezdxf


def polyline_info(entity):
    points = [(v.dxf.location.x, v.dxf.location.y) for v in entity.vertices]
    n = len(points)
    length = 0.0
    for i in range(n if entity.is_closed else n - 1):
        x0, y0 = points[i]
        x1, y1 = points[(i + 1) % n]
        length += math.hypot(x1 - x0, y1 - y0)
    return {"length": length, "vertices": n, "closed": bool(entity.is_closed)}


def main(path):
    doc = ezdxf.readfile(path)
    out = {
        "dxfversion": doc.dxfversion,
        "insunits": doc.header.get("$INSUNITS"),
        "measurement": doc.header.get("$MEASUREMENT"),
        "blocks": {},
        "inserts": [],
    }
    for block in doc.blocks:
        if block.name.startswith("*") or block.name.startswith("$"):
            continue
        info = {"cut": [], "sew": [], "notches": [], "grain": [], "texts": [], "other_layers": []}
        for e in block:
            kind, layer = e.dxftype(), e.dxf.layer
            if kind == "POLYLINE" and layer == "1":
                info["cut"].append(polyline_info(e))
            elif kind == "POLYLINE" and layer == "14":
                info["sew"].append(polyline_info(e))
            elif kind == "LINE" and layer == "4":
                info["notches"].append([e.dxf.start.x, e.dxf.start.y, e.dxf.end.x, e.dxf.end.y])
            elif kind == "LINE" and layer == "7":
                info["grain"].append([e.dxf.start.x, e.dxf.start.y, e.dxf.end.x, e.dxf.end.y])
            elif kind == "TEXT" and layer == "1":
                info["texts"].append(e.dxf.text)
            else:
                info["other_layers"].append(kind + "@" + layer)
        out["blocks"][block.name] = info
    for insert in doc.modelspace().query("INSERT"):
        out["inserts"].append([insert.dxf.name, insert.dxf.insert.x, insert.dxf.insert.y])
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1])

"""Reads a pattern DXF with ezdxf and prints what it found as JSON (for pattern_dxf_test).

Usage: /usr/bin/python3 pattern_dxf_check.py FILE.dxf
Output: {"dxfversion", "insunits", "measurement", "blocks": {name: {"cut": [...],
"sew": [...], "cut_closed", "sew_closed", "notches": [[x1, y1, x2, y2], ...],
"grain": [...], "texts": [...], "annotations": [[text, x, y, height, angle], ...],
"system_texts": [[text, x, y, height, angle], ...], "turn_points": [[x, y], ...],
"curve_points": [[x, y], ...], "sew_points": [[x, y], ...], "other_layers": [...]}},
"inserts": [[name, x, y], ...], "style_texts": [...]}
where "cut"/"sew" hold the outline length (mm) and vertex count of each POLYLINE on
layer 1 / 14, "sew_points" the vertices of the sew line, "texts" the TEXT contents on
layer 1 and "system_texts" the same with their placement, "annotations" the TEXTs on
layer 15, "turn_points"/"curve_points" the POINTs on layer 2 / 3, "style_texts" the
TEXTs of the ENTITIES section.
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


def text_info(entity):
    return [entity.dxf.text, entity.dxf.insert.x, entity.dxf.insert.y, entity.dxf.height,
            entity.dxf.rotation]


def main(path):
    doc = ezdxf.readfile(path)
    out = {
        "dxfversion": doc.dxfversion,
        "insunits": doc.header.get("$INSUNITS"),
        "measurement": doc.header.get("$MEASUREMENT"),
        "blocks": {},
        "inserts": [],
        "style_texts": [e.dxf.text for e in doc.modelspace().query("TEXT")],
    }
    for block in doc.blocks:
        if block.name.startswith("*") or block.name.startswith("$"):
            continue
        info = {"cut": [], "sew": [], "notches": [], "grain": [], "texts": [], "annotations": [],
                "system_texts": [], "turn_points": [], "curve_points": [], "sew_points": [],
                "other_layers": []}
        for e in block:
            kind, layer = e.dxftype(), e.dxf.layer
            if kind == "POLYLINE" and layer == "1":
                info["cut"].append(polyline_info(e))
            elif kind == "POLYLINE" and layer == "14":
                info["sew"].append(polyline_info(e))
                info["sew_points"] = [[v.dxf.location.x, v.dxf.location.y] for v in e.vertices]
            elif kind == "LINE" and layer == "4":
                info["notches"].append([e.dxf.start.x, e.dxf.start.y, e.dxf.end.x, e.dxf.end.y])
            elif kind == "LINE" and layer == "7":
                info["grain"].append([e.dxf.start.x, e.dxf.start.y, e.dxf.end.x, e.dxf.end.y])
            elif kind == "TEXT" and layer == "1":
                info["texts"].append(e.dxf.text)
                info["system_texts"].append(text_info(e))
            elif kind == "TEXT" and layer == "15":
                info["annotations"].append(text_info(e))
            elif kind == "POINT" and layer == "2":
                info["turn_points"].append([e.dxf.location.x, e.dxf.location.y])
            elif kind == "POINT" and layer == "3":
                info["curve_points"].append([e.dxf.location.x, e.dxf.location.y])
            else:
                info["other_layers"].append(kind + "@" + layer)
        out["blocks"][block.name] = info
    for insert in doc.modelspace().query("INSERT"):
        out["inserts"].append([insert.dxf.name, insert.dxf.insert.x, insert.dxf.insert.y])
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1])

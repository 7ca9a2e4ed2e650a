"""Reads a PLY file with meshio (Debian's python3-meshio) and prints its triangles and
per-face data as JSON, numbers in repr form so that doubles read back exactly.
Usage: /usr/bin/python3 fit_ply_read.py FILE.ply OUT.json"""
import json
import sys

import meshio

mesh = meshio.read(sys.argv[1])
triangles = [block for block in mesh.cells if block.type == "triangle"]
if len(triangles) != 1:
    sys.exit(f"expected one triangle block, got {[block.type for block in mesh.cells]}")
out = {
    "points": mesh.points.tolist(),
    "triangles": triangles[0].data.tolist(),
    "cell_data": {name: [float(v) for v in arrays[0]] for name, arrays in mesh.cell_data.items()},
}
with open(sys.argv[2], "w") as f:
    json.dump(out, f)

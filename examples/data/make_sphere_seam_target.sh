#!/bin/sh
# Makes sphere_seam_target.obj, the shape target of examples/optimize_sphere_seam_stiffness.json
# (paper Fig. 8): the three-piece cover of examples/cover_sphere_three_pieces.json simulated on
# its soft sphere WITHOUT seam stiffness; the garment's equilibrium surface (on the body's limit
# surface) is written as a plain OBJ (m). Run from anywhere after `make build`; TIGHTFIT names
# another binary.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
tightfit=${TIGHTFIT:-$here/../../build/release/tightfit}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$tightfit" simulate "$here/../cover_sphere_three_pieces.json" --out "$tmp/fit" > "$tmp/log"
python3 - "$tmp/fit/garment.ply" "$here/sphere_seam_target.obj" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
end = lines.index("end_header")
counts = {}
for line in lines[:end]:
    words = line.split()
    if words[:1] == ["element"]:
        counts[words[1]] = int(words[2])
body = lines[end + 1:]
nv, nf = counts["vertex"], counts["face"]
with open(sys.argv[2], "w") as out:
    out.write("# three-piece cover on the soft sphere without seam stiffness (make_sphere_seam_target.sh)\n")
    for line in body[:nv]:
        x, y, z = line.split()[:3]
        out.write(f"v {x} {y} {z}\n")
    for line in body[nv:nv + nf]:
        words = line.split()
        assert words[0] == "3", "triangles expected"
        out.write("f " + " ".join(str(int(w) + 1) for w in words[1:4]) + "\n")
PY
echo "wrote $here/sphere_seam_target.obj"

#!/usr/bin/env python3
"""Makes slim_legs_target.obj, the shape target of examples/optimize_pants_shape.json
(paper Fig. 4, shapewear): the MakeHuman male legs body (data/bodies/mh_legs_male.obj, m,
y up) slimmed at the hips and thighs.

Slimming: every vertex moves towards the centre of its horizontal slice of its own half
of the body (x < 0 or x >= 0, slices 1 cm high: each leg below the crotch, each half of
the hips above it), so the circumference there shrinks by the same factor. The factor
is 1 - 0.04 w(y): w = 1 for 0.70 <= y <= 0.92 m (upper thighs, hips, seat), falling to
0 with a cosine ramp by y = 0.50 m (above the knee) and y = 1.00 m (the waist): a 4 %
hip and thigh reduction, the waist, knees and calves unchanged.

Usage: make_slim_legs_target.py [BODY.obj] [OUT.obj]  (defaults: the repository's files)
"""
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
body = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "data", "bodies", "mh_legs_male.obj")
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "slim_legs_target.obj")

REDUCTION = 0.04
FULL = (0.70, 0.92)   # m: full reduction
ZERO = (0.50, 1.00)   # m: no reduction outside
SLICE = 0.01          # m


def weight(y):
    if FULL[0] <= y <= FULL[1]:
        return 1.0
    if ZERO[0] < y < FULL[0]:
        return 0.5 - 0.5 * math.cos(math.pi * (y - ZERO[0]) / (FULL[0] - ZERO[0]))
    if FULL[1] < y < ZERO[1]:
        return 0.5 + 0.5 * math.cos(math.pi * (y - FULL[1]) / (ZERO[1] - FULL[1]))
    return 0.0


vertices, faces = [], []
for line in open(body):
    words = line.split()
    if not words:
        continue
    if words[0] == "v":
        vertices.append([float(w) for w in words[1:4]])
    elif words[0] == "f":
        faces.append([int(w.split("/")[0]) for w in words[1:]])

def key(v):
    return (v[0] >= 0.0, int(math.floor(v[1] / SLICE)))

sums = {}
for v in vertices:
    s = sums.setdefault(key(v), [0.0, 0.0, 0])
    s[0] += v[0]
    s[1] += v[2]
    s[2] += 1

with open(out, "w") as f:
    f.write("# mh_legs_male.obj slimmed %g %% at hips and thighs (make_slim_legs_target.py)\n" % (100 * REDUCTION))
    for v in vertices:
        sx, sz, n = sums[key(v)]
        cx, cz = sx / n, sz / n
        scale = 1.0 - REDUCTION * weight(v[1])
        f.write("v %.7f %.7f %.7f\n" % (cx + scale * (v[0] - cx), v[1], cz + scale * (v[2] - cz)))
    for face in faces:
        f.write("f " + " ".join(str(i) for i in face) + "\n")
print("wrote", out)

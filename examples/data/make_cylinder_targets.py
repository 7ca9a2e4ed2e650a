#!/usr/bin/env python3
"""Writes the shape targets of the Fig. 3 examples (paper Sec. 6.1) as OBJ files:
open surfaces of revolution about the z axis, in metres, outward-facing triangles.

  tapered_cylinder.obj   r(z) = R_MEAN - TAPER * z / HALF          (linear, cone)
  hourglass_cylinder.obj r(z) = R_MEAN - WAIST * cos(pi z / HALF)   (waist at z = 0)

HALF = 0.1 m is the half length of the garment (it covers -0.1 <= z <= 0.1) on the
body of rest radius R0 = 0.05 m. Both profiles have the mean radius R_MEAN over the
garment, only 1 mm inside the body's rest surface: the body is nearly incompressible
(nu = 0.49) and can mostly only move its volume along the axis (paper Sec. 6.1:
"volume changes cannot be achieved in this way"). The surfaces run past the garment (|z| <= LENGTH/2)
so that IMLS (radius 10 mm) sees target points on both sides of the cuffs.

Usage: python3 make_cylinder_targets.py [OUTDIR]   (default: this script's folder)
"""
import math
import os
import sys

R0 = 0.05        # m, body rest radius (examples/optimize_cylinder_*.json)
R_MEAN = 0.049   # m, mean target radius over the garment (1 mm of uniform compression)
HALF = 0.1       # m, half length of the garment
LENGTH = 0.26    # m, length of the target surface
TAPER = 0.0015   # m, radius change from the middle to either cuff (tapered)
WAIST = 0.0015   # m, radius reduction at the waist and increase at the cuffs (hourglass)
SPACING = 0.004  # m, target point spacing along the axis and around


def tapered(z):
    return R_MEAN - TAPER * z / HALF


def hourglass(z):
    return R_MEAN - WAIST * math.cos(math.pi * max(-HALF, min(HALF, z)) / HALF)


def write_revolution(path, radius):
    n_around = int(math.ceil(2.0 * math.pi * R0 / SPACING))
    n_along = int(math.ceil(LENGTH / SPACING)) + 1
    with open(path, "w") as out:
        out.write("# %s: surface of revolution about z, metres (make_cylinder_targets.py)\n"
                  % os.path.basename(path))
        for j in range(n_along):
            z = -LENGTH / 2 + LENGTH * j / (n_along - 1)
            r = radius(z)
            for i in range(n_around):
                a = 2.0 * math.pi * i / n_around
                out.write("v %.9f %.9f %.9f\n" % (r * math.cos(a), r * math.sin(a), z))
        for j in range(n_along - 1):
            for i in range(n_around):
                a = j * n_around + i + 1
                b = j * n_around + (i + 1) % n_around + 1
                c = b + n_around
                d = a + n_around
                # counter-clockwise seen from outside: normals point away from the axis
                out.write("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    write_revolution(os.path.join(outdir, "tapered_cylinder.obj"), tapered)
    write_revolution(os.path.join(outdir, "hourglass_cylinder.obj"), hourglass)


if __name__ == "__main__":
    main()

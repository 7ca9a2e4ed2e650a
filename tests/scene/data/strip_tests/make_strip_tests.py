#!/usr/bin/env python3
"""Writes the synthetic strip tests of tests/scene/fabric_fit_test.cpp: a knit whose
curves are known, T(e) = a e + b e^3 N/m loading (wale a=300, b=400; course 120, 150;
bias 60, 80), pulled by 50 mm wide strips over a 100 mm gauge length in three cycles; the
first two cycles load a little stiffer (as a knit does before it settles); unloading
follows T(e) ((e - r) / (top - r))^0.6, below loading, zero under the residual strain
r = 0.06 top. Forces carry Gaussian noise of 2 mN (seeded).
  knit_cycles.csv            every direction, with a cycle column, ';'-separated
  knit_no_cycle_column.csv   wale and course only, no cycle column, ','-separated
Usage: python3 make_strip_tests.py   (in this folder)"""
import random

random.seed(7)
WIDTH, GAUGE = 50.0, 100.0  # mm
CURVES = {"wale": (300.0, 400.0), "course": (120.0, 150.0), "bias": (60.0, 80.0)}


def load(d, e):
    a, b = CURVES[d]
    return a * e + b * e ** 3


def unload(d, e, top):
    r = 0.06 * top
    return 0.0 if e <= r else load(d, e) * ((e - r) / (top - r)) ** 0.6


rows = []
for d, top in (("wale", 0.8), ("course", 1.0), ("bias", 0.9)):
    for cycle in (1, 2, 3):
        n = 60
        for i in range(n + 1):
            e = top * i / n
            t = load(d, e) * (1.0 + 0.04 * (3 - cycle))
            rows.append((d, e * GAUGE, t * WIDTH / 1000 + random.gauss(0, 0.002), cycle))
        for i in range(1, n + 1):
            e = top * (1 - i / n)
            t = unload(d, e, top)
            rows.append((d, e * GAUGE, max(t * WIDTH / 1000 + random.gauss(0, 0.002), 0.0), cycle))
with open("knit_cycles.csv", "w") as f:
    f.write("direction;extension_mm;force_n;cycle\n")
    for d, x, force, c in rows:
        f.write(f"{d};{x:.4f};{force:.5f};{c}\n")
with open("knit_no_cycle_column.csv", "w") as f:
    f.write("Direction,Extension_mm,Force_N\n")
    for d, x, force, c in rows:
        if d != "bias":
            f.write(f"{d},{x:.4f},{force:.5f}\n")

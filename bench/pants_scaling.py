#!/usr/bin/env python3
"""Scaling and mesh convergence of pattern optimization: a benchmark.

Runs `tightfit optimize` on examples/optimize_pants_stretch.json with the garment edge
length set to each value of --edges (mm) and the body surface kept at the example's
25 mm (coarser than the garment, the paper's Sec. 7 rule), each for --iterations L-BFGS
iterations, under /usr/bin/time for the peak RSS. Prints per resolution: garment
triangles, per-iteration wall time (s), peak RSS (MB), the fitted exponent of
per-iteration time against triangles, and — for runs long enough to converge — the
final objective and the largest distance (mm) between corresponding sew lines of the
optimized pieces at successive resolutions. Writes bench_pants_scaling.json.

Usage: bench/pants_scaling.py BUILD/tightfit [--edges 25 18 12.5 9] [--iterations 5]
       [--out out/bench/pants_scaling]
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def scene_variant(edge_mm, out_dir):
    with open(os.path.join(ROOT, "examples", "optimize_pants_stretch.json")) as f:
        scene = json.load(f)
    scene["body"]["mesh"] = os.path.join(ROOT, "data", "bodies", "mh_legs_male.obj")
    scene["garment"]["pattern"]["edge_length"] = edge_mm / 1000.0
    scene["description"] = f"pants stretch example, garment edge {edge_mm} mm"
    path = os.path.join(out_dir, f"pants_{edge_mm}mm.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def run(binary, scene, out, iterations):
    cmd = ["/usr/bin/time", "-v", binary, "optimize", scene, "--out", out,
           "--max-iterations", str(iterations)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        raise SystemExit(f"tightfit optimize failed on {scene}")
    rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
    with open(os.path.join(out, "history.json")) as f:
        history = json.load(f)
    its = [h for h in history["iterations"] if h["iteration"] > 0] if isinstance(history, dict) \
        else [h for h in history if h["iteration"] > 0]
    with open(os.path.join(out, "result.json")) as f:
        result = json.load(f)
    return rss_kb, its, result


def polyline_distance(a, b):
    """Symmetric Hausdorff distance between two closed polylines (lists of [x, y])."""
    def dense(p, step=0.5):
        out = []
        for i in range(len(p)):
            x0, y0 = p[i]
            x1, y1 = p[(i + 1) % len(p)]
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / step))
            out += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(n)]
        return out

    def one_way(p, q):
        worst = 0.0
        for x, y in p:
            best = min((x - u) ** 2 + (y - v) ** 2 for u, v in q)
            worst = max(worst, best)
        return math.sqrt(worst)

    da, db = dense(a), dense(b)
    return max(one_way(da[::4], db), one_way(db[::4], da))


def sew_lines(out):
    with open(os.path.join(out, "pieces.json")) as f:
        pieces = json.load(f)["pieces"]
    return {p["name"]: p["sew_line_mm"] for p in pieces}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("--edges", type=float, nargs="+", default=[25, 18, 12.5, 9])
    ap.add_argument("--iterations", type=int, default=5)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench", "pants_scaling"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for edge in args.edges:
        scene = scene_variant(edge, args.out)
        out = os.path.join(args.out, f"run_{edge}mm")
        rss_kb, its, result = run(args.binary, scene, out, args.iterations)
        per_it = (its[-1]["seconds"] - its[0]["seconds"]) / max(1, len(its) - 1) if len(its) > 1 \
            else its[0]["seconds"]
        row = {
            "edge_mm": edge,
            "garment_triangles": result["counts"]["garment_triangles"],
            "dofs": result["counts"]["dofs"],
            "iterations": len(its),
            "seconds_per_iteration": per_it,
            "newton_per_iteration": sum(h["newton_iterations"] for h in its) / len(its),
            "trials_per_iteration": sum(h["line_search_trials"] for h in its) / len(its),
            "factorizations_per_iteration": sum(h.get("factorizations", 0) for h in its) / len(its),
            "peak_rss_mb": rss_kb / 1024.0,
            "objective_final": result["optimization"]["objective_final"],
            "objective_ratio": result["optimization"]["objective_final"]
            / result["optimization"]["objective_initial"],
            "out": out,
        }
        rows.append(row)
        print(f"edge {edge:5.1f} mm: {row['garment_triangles']:6d} triangles, "
              f"{row['seconds_per_iteration']:7.2f} s/it, newton {row['newton_per_iteration']:.2f}/it, "
              f"trials {row['trials_per_iteration']:.2f}/it, chol {row['factorizations_per_iteration']:.2f}/it, "
              f"peak {row['peak_rss_mb']:.0f} MB, objective {row['objective_final']:.4e} "
              f"(ratio {row['objective_ratio']:.4f})", flush=True)
    if len(rows) >= 2:
        xs = [math.log(r["garment_triangles"]) for r in rows]
        ys = [math.log(r["seconds_per_iteration"]) for r in rows]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
        print(f"per-iteration time ~ n^{slope:.2f} (n = garment triangles)")
    else:
        slope = None
    convergence = []
    for a, b in zip(rows, rows[1:]):
        la, lb = sew_lines(a["out"]), sew_lines(b["out"])
        worst = max(polyline_distance(la[k], lb[k]) for k in la if k in lb)
        convergence.append({"from_mm": a["edge_mm"], "to_mm": b["edge_mm"], "max_sew_line_distance_mm": worst})
        print(f"sew lines {a['edge_mm']} mm vs {b['edge_mm']} mm: largest distance {worst:.2f} mm")
    with open(os.path.join(args.out, "bench_pants_scaling.json"), "w") as f:
        json.dump({"rows": rows, "exponent": slope, "convergence": convergence}, f, indent=1)


if __name__ == "__main__":
    main()

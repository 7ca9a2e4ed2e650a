#!/usr/bin/env python3
"""Full-body-size simulation benchmark: a cold-start `tightfit
simulate` of the 12-piece wetsuit (examples/optimize_wetsuit_regular.json) on the
MakeHuman regular body at a resolution chosen on the command line.

The example runs at 30 mm (2k garment triangles, about 10k tets); the benchmark sets the
body's surface edge (--body-mm) and the pattern's edge (--garment-mm), keeps everything
else of the example (crops, layout, fabric, the 0.9 scale), lets Newton take up to
--max-newton iterations, and runs the command under /usr/bin/time for the peak RSS.
Prints and writes (OUT/full_body_simulate.json): garment triangles, body tets, DOFs,
Newton iterations (of them chord steps) and factorizations, whether it converged and
its final force residual against the tolerance, wall time and its split (assembly,
factorization, solve, line search), the Hessian's and the factor's nonzeros, the peak
RSS, the threads and the BLAS.

Usage: bench/full_body_simulate.py BUILD/tightfit [--body-mm 12] [--garment-mm 7.5]
       [--max-newton 200] [--threads N] [--out out/bench/full_body]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
EXAMPLE = os.path.join(ROOT, "examples", "optimize_wetsuit_regular.json")


def absolute(path):
    """A path of the example, made absolute (the variant is written elsewhere)."""
    return os.path.normpath(os.path.join(os.path.dirname(EXAMPLE), path))


def scene_variant(body_mm, garment_mm, max_newton, out_dir):
    with open(EXAMPLE) as f:
        scene = json.load(f)
    scene["body"]["mesh"] = absolute(scene["body"]["mesh"])
    scene["body"]["edge_length"] = body_mm / 1000.0
    for key in ("mesh", "weights", "joints"):
        scene["rig"][key] = absolute(scene["rig"][key])
    scene["garment"]["layout"] = absolute(scene["garment"]["layout"])
    scene["garment"]["pattern"]["edge_length"] = garment_mm / 1000.0
    scene["solver"]["max_iterations"] = max_newton
    scene.pop("optimize", None)
    scene["description"] = (f"full-body benchmark: the wetsuit example with the body at "
                            f"{body_mm} mm and the pattern at {garment_mm} mm")
    path = os.path.join(out_dir, f"wetsuit_body{body_mm}mm_garment{garment_mm}mm.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("binary")
    ap.add_argument("--body-mm", type=float, default=12.0)
    ap.add_argument("--garment-mm", type=float, default=7.5)
    ap.add_argument("--max-newton", type=int, default=200)
    ap.add_argument("--threads", type=int)
    ap.add_argument("--out", default=os.path.join("out", "bench", "full_body"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = scene_variant(a.body_mm, a.garment_mm, a.max_newton, a.out)
    run_dir = os.path.join(a.out, "run")
    if os.path.exists(run_dir):
        sys.exit(f"full_body_simulate: {run_dir} exists; remove it or pass another --out")
    cmd = ["/usr/bin/time", "-v", a.binary, "simulate", scene, "--out", run_dir]
    if a.threads:
        cmd += ["--threads", str(a.threads)]
    start = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    rss_kb = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    if p.returncode != 0 and not os.path.exists(os.path.join(run_dir, "result.json")):
        sys.stderr.write(p.stdout + p.stderr)
        sys.exit(f"full_body_simulate: tightfit simulate failed (exit {p.returncode})")
    with open(os.path.join(run_dir, "result.json")) as f:
        result = json.load(f)
    newton = result["newton"]
    row = {
        "scene": scene,
        "exit_code": p.returncode,
        "body_mm": a.body_mm,
        "garment_mm": a.garment_mm,
        "garment_triangles": result["counts"]["garment_triangles"],
        "body_tets": result["counts"]["body_tets"],
        "dofs": result["counts"]["dofs"],
        "newton_iterations": newton["iterations"],
        "chord_steps": newton.get("chord_steps"),
        "factorizations": newton.get("factorizations"),
        "krylov_iterations": newton.get("krylov_iterations"),
        "converged": newton["converged"],
        "message": newton["message"],
        "force_residual_n": newton["final_force_residual_n"],
        "force_tolerance_n": newton["force_tolerance_n"],
        "hessian_nonzeros": newton["hessian_nonzeros"],
        "factor_nonzeros": newton["factor_nonzeros"],
        "newton_seconds": newton["seconds"],
        "command_seconds": result["seconds"],
        "wall_s": wall,
        "peak_rss_mb": int(rss_kb.group(1)) / 1024 if rss_kb else None,
        "compute": result.get("compute"),
    }
    with open(os.path.join(a.out, "full_body_simulate.json"), "w") as f:
        json.dump(row, f, indent=1)
    print(f"{row['garment_triangles']} garment triangles, {row['body_tets']} tets, "
          f"{row['dofs']} DOFs: {row['newton_iterations']} Newton iterations "
          f"({row['chord_steps']} chord steps, {row['factorizations']} factorizations), "
          f"converged {row['converged']} (residual {row['force_residual_n']:.3g} N, "
          f"tolerance {row['force_tolerance_n']:.3g} N), wall {wall:.1f} s, "
          f"peak RSS {row['peak_rss_mb']:.0f} MB")
    print("Newton time split (s):", json.dumps(row["newton_seconds"]))
    print("Hessian / factor nonzeros:", row["hessian_nonzeros"], "/", row["factor_nonzeros"])
    return 0 if row["converged"] else 1


if __name__ == "__main__":
    sys.exit(main())

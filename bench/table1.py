#!/usr/bin/env python3
"""The Table 1 runner: runs the rows of the paper's Table 1 (plus the graduated stocking)
and writes docs/results.md, which is generated, never edited by hand.

Each row is one example of examples/: `tightfit optimize SCENE`, or for the four wetsuit
rows `tightfit grade examples/optimize_wetsuit_regular.json examples/grading/bodies_full.json
--body NAME`. Per row the results file gives the paper's ratio (final / initial objective),
iterations, seconds per iteration and wall time (iterations x s/it), and tightfit's ratio,
iterations, s/it, optimization and process wall time, the rule that ended the run, and the
time (and iteration) at which tightfit first reached the paper's ratio (from history.json),
with the machine (CPU model, cores, memory) and the commit. A row that fails is reported
with its error; rows not selected with --rows are listed as not run.

Every run leaves WORK/ROW/runner.json (command, exit code, wall time, error) beside the
run's outputs; --report-only rebuilds the results file from such a folder without running.

Usage:
  bench/table1.py BIN [--rows ID,ID...] [--time-limit S] [--out docs/results.md]
                  [--work out/table1] [--readme README.md]
  bench/table1.py --report-only WORK [--out FILE]
  bench/table1.py --list
The summary between the markers <!-- table1-summary:begin --> and
<!-- table1-summary:end --> of the results file is the short table the README shows: the
runner copies it into README.md's block between the same markers when it writes
docs/results.md (--readme FILE for another file); `make test` checks that the two agree
(scripts/check_docs.py).
"""
import functools
import argparse
import datetime
import json
import os
import platform
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

SUMMARY_BEGIN = "<!-- table1-summary:begin -->"
SUMMARY_END = "<!-- table1-summary:end -->"
WETSUIT_DESIGN = "examples/optimize_wetsuit_regular.json"
WETSUIT_BODIES = "examples/grading/bodies_full.json"
# A run past the time limit is asked to stop (SIGINT: tightfit then writes the outputs of its
# last iteration) and killed if it has not ended this many seconds later.
STOP_GRACE_SECONDS = 300


def row(id_, model, iterations, seconds_per_iteration, initial, final, scene=None, body=None):
    return {"id": id_, "model": model, "scene": scene, "body": body,
            "paper": None if iterations is None else {
                "iterations": iterations, "seconds_per_iteration": seconds_per_iteration,
                "initial": initial, "final": final}}


# The paper's Table 1 (# iterations, time per iteration [s], initial and final objective).
ROWS = [
    row("cylinder_tapered", "Cylinder tapered (Fig. 3b)", 346, 12.2, 5433.58, 106.952,
        scene="examples/optimize_cylinder_tapered.json"),
    row("cylinder_hourglass", "Cylinder hourglass (Fig. 3c)", 386, 10.1, 2241.66, 222.638,
        scene="examples/optimize_cylinder_hourglass.json"),
    row("pants_stretch", "Pants stretch (Fig. 1)", 903, 6.34, 133.06, 5.7029,
        scene="examples/optimize_pants_stretch.json"),
    row("pants_seam_traction", "Pants seam traction (Fig. 1)", 4160, 5.87, 38.6195, 28.4453,
        scene="examples/optimize_pants_seam_traction.json"),
    row("pants_shape", "Pants shape (Fig. 4)", 1408, 19.2, 66.9126, 14.3992,
        scene="examples/optimize_pants_shape.json"),
    row("sphere_pressure", "Sphere pressure (Fig. 5)", 2714, 4.66, 9547.41, 205.544,
        scene="examples/optimize_sphere_pressure.json"),
    row("sphere_shape", "Sphere shape (Fig. 8)", 1001, 22.3, 22524.6, 217.663,
        scene="examples/optimize_sphere_seam_stiffness.json"),
    row("mask_pressure", "Mask pressure (Fig. 6)", 849, 6.40, 55.4356, 1.54963,
        scene="examples/optimize_mask_pressure.json"),
    row("pants_sliding", "Sliding pants (Fig. 7)", 914, 7.48, 120.566, 5.22695,
        scene="examples/optimize_pants_sliding.json"),
    row("wetsuit_regular", "Wetsuit regular (Fig. 9)", 1629, 5.84, 130.225, 19.7035,
        body="regular"),
    row("wetsuit_athletic", "Wetsuit athletic (Fig. 9)", 1735, 5.57, 139.744, 21.1511,
        body="athletic"),
    row("wetsuit_overweight", "Wetsuit overweight (Fig. 9)", 1353, 6.60, 177.552, 25.8128,
        body="overweight"),
    row("wetsuit_kid", "Wetsuit kid (Fig. 9)", 1561, 5.72, 115.961, 18.3544, body="child"),
    row("stocking_graduated", "Graduated stocking (not in the paper)", None, None, None, None,
        scene="examples/optimize_stocking_graduated.json"),
]
ROW_IDS = [r["id"] for r in ROWS]


# ----------------------------------------------------------------------------- running

def load_average():
    """The 1-minute load average (other work on the machine slows every s/it), or None."""
    try:
        with open("/proc/loadavg") as f:
            return float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def supports_time_limit(binary, command):
    try:
        text = subprocess.run([binary, command, "--help"], capture_output=True, text=True,
                              timeout=60).stdout
    except (OSError, subprocess.SubprocessError):
        return False
    return "--time-limit" in text


def command_of(r, binary, folder, time_limit, own_time_limit):
    if r["body"]:
        cmd = [binary, "grade", os.path.join(ROOT, WETSUIT_DESIGN),
               os.path.join(ROOT, WETSUIT_BODIES), "--out", folder, "--body", r["body"],
               "--force"]
    else:
        cmd = [binary, "optimize", os.path.join(ROOT, r["scene"]), "--out", folder, "--force"]
    if time_limit and own_time_limit:
        cmd += ["--time-limit", str(time_limit)]
    return cmd


def run_row(r, binary, work, time_limit):
    """Runs one row in WORK/ID and writes WORK/ID/runner.json."""
    folder = os.path.join(work, r["id"])
    # A fresh folder: tightfit grade would skip a body graded there or resume its checkpoint.
    if os.path.isdir(folder):
        if os.listdir(folder) and not os.path.isfile(os.path.join(folder, "runner.json")):
            raise SystemExit(f"table1: {folder} exists and is not a run of bench/table1.py: "
                             "give another --work")
        shutil.rmtree(folder)
    os.makedirs(folder)
    subcommand = "grade" if r["body"] else "optimize"
    own_limit = bool(time_limit) and supports_time_limit(binary, subcommand)
    cmd = command_of(r, binary, folder, time_limit, own_limit)
    log_path = os.path.join(folder, "runner.log")
    record = {"row": r["id"], "command": cmd, "time_limit": time_limit,
              "time_limit_by": None if not time_limit else ("tightfit" if own_limit else "runner")}
    record["load_average_at_start"] = load_average()
    record["machine"] = machine()
    record["commit"] = commit()
    record["returncode"] = None  # until the run ends
    runner_file = os.path.join(folder, "runner.json")
    with open(runner_file, "w") as f:
        json.dump(record, f, indent=1)
    start = time.monotonic()
    stopped = False
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT,
                                start_new_session=True)
        deadline = None if own_limit or not time_limit else start + time_limit
        while True:
            try:
                proc.wait(timeout=1.0 if deadline else None)
                break
            except subprocess.TimeoutExpired:
                now = time.monotonic()
                if not stopped and now > deadline:
                    os.killpg(proc.pid, signal.SIGINT)
                    stopped = True
                elif stopped and now > deadline + STOP_GRACE_SECONDS:
                    os.killpg(proc.pid, signal.SIGKILL)
    record["wall_seconds"] = time.monotonic() - start
    record["returncode"] = proc.returncode
    record["stopped_by_runner"] = stopped
    if proc.returncode != 0:
        with open(log_path) as f:
            lines = [line.rstrip() for line in f if line.strip()]
        record["error"] = " / ".join(lines[-3:]) or f"exit code {proc.returncode}"
    with open(runner_file, "w") as f:
        json.dump(record, f, indent=1)
    return record


# ----------------------------------------------------------------------------- parsing

def outputs_folder(r, folder):
    return os.path.join(folder, "bodies", r["body"]) if r["body"] else folder


def stop_rule(optimization, runner):
    """The rule that ended the run, in words."""
    for key in ("stop_rule", "stop_reason"):
        text = optimization.get(key)
        if isinstance(text, str) and text:
            words = text
            break
    else:
        words = ("converged" if optimization.get("converged") else
                 "interrupted" if optimization.get("interrupted") else "iteration limit")
    if runner.get("stopped_by_runner"):
        words += " (stopped at the runner's time limit)"
    return words


def parse_row(r, folder):
    """The measured result of one row from its run folder, or None when it was not run."""
    runner_file = os.path.join(folder, "runner.json")
    if not os.path.isfile(runner_file):
        return None
    with open(runner_file) as f:
        runner = json.load(f)
    out = {"runner": runner}
    if runner.get("returncode", 0) is None:
        out["error"] = "the runner was stopped before this row's run ended"
        return out
    files = outputs_folder(r, folder)
    try:
        with open(os.path.join(files, "result.json")) as f:
            result = json.load(f)
        with open(os.path.join(files, "history.json")) as f:
            history = json.load(f)
        o = result["optimization"]
        initial, final = float(o["objective_initial"]), float(o["objective_final"])
        iterations = int(o["iterations"])
        seconds = float(o["seconds_optimization"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        reason = runner.get("error") or f"no readable result: {e}"
        out["error"] = reason
        return out
    out.update({"initial": initial, "final": final,
                "ratio": final / initial if initial > 0 else None,
                "iterations": iterations, "seconds": seconds,
                "seconds_per_iteration": seconds / iterations if iterations > 0 else None,
                "stop": stop_rule(o, runner)})
    if runner.get("returncode", 0) != 0 and not runner.get("stopped_by_runner"):
        out["warning"] = runner.get("error")
    paper = r["paper"]
    if paper and initial > 0:
        target = paper["final"] / paper["initial"]
        for it in history.get("iterations", []):
            if float(it["objective"]) / initial <= target:
                out["reached"] = {"iteration": int(it["iteration"]), "seconds": float(it["seconds"])}
                break
    return out


# ----------------------------------------------------------------------------- writing

def fmt(x, digits=3):
    if x is None:
        return "–"
    return f"{x:.{digits}g}"


def seconds_text(s):
    if s is None:
        return "–"
    if s >= 3600:
        return f"{s / 3600:.1f} h"
    if s >= 60:
        return f"{s / 60:.1f} min"
    return f"{s:.1f} s"


def machine():
    model, cores = "unknown CPU", os.cpu_count()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    memory = "unknown memory"
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    memory = f"{int(line.split()[1]) / 1024 ** 2:.1f} GiB"
                    break
    except OSError:
        pass
    return f"{model}, {cores} logical cores, {memory} ({platform.system()} {platform.release()})"


@functools.lru_cache(maxsize=None)
def commit():
    """The source's commit when the runner started (one for all rows)."""
    try:
        sha = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return sha + (" (with uncommitted changes)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown (not a git checkout)"


def row_cells(r, m):
    p = r["paper"]
    paper = ([fmt(p["final"] / p["initial"]), str(p["iterations"]),
              f"{p['seconds_per_iteration']:.3g}",
              seconds_text(p["iterations"] * p["seconds_per_iteration"])]
             if p else ["–"] * 4)
    if m is None:
        return paper + ["not run"] + [""] * 6
    if "error" in m:
        return paper + ["**failed**"] + [""] * 5 + [m["error"].replace("|", "\\|")]
    reached = m.get("reached")
    reached_text = (f"{seconds_text(reached['seconds'])} (it. {reached['iteration']})"
                    if reached else ("not reached" if p else "–"))
    stop = m["stop"] + (f"; exit: {m['warning']}" if m.get("warning") else "")
    return paper + [fmt(m["ratio"]), str(m["iterations"]), fmt(m["seconds_per_iteration"]),
                    seconds_text(m["seconds"]), seconds_text(m["runner"].get("wall_seconds")),
                    reached_text, stop.replace("|", "\\|")]


def report(measured, command_line):
    run = [r["id"] for r in ROWS if measured.get(r["id"]) is not None]
    not_run = [r["id"] for r in ROWS if measured.get(r["id"]) is None]
    limits = {(m["runner"].get("time_limit"), m["runner"].get("time_limit_by"))
              for m in measured.values() if m}
    loads = [m["runner"].get("load_average_at_start") for m in measured.values() if m]
    loads = [x for x in loads if x is not None]
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    # The machine and commit the rows ran on (recorded by each run), else this one's.
    machines = sorted({m["runner"].get("machine") or machine() for m in measured.values() if m})
    commits = sorted({m["runner"].get("commit") or commit() for m in measured.values() if m})
    machines, commits = machines or [machine()], commits or [commit()]
    lines = [
        "# Results: the paper's Table 1",
        "",
        "<!-- Generated by bench/table1.py; do not edit by hand: rerun the runner. -->",
        "",
        f"Generated by `{command_line}` on {now}.",
        "",
        f"* Machine: {'; '.join(machines)}.",
        f"* Commit: {'; '.join(commits)}.",
        f"* Rows run: {', '.join(run) if run else 'none'}.",
        f"* Rows **not run** in this file: {', '.join(not_run) if not_run else 'none'}.",
        "* Time limit per row: " + (", ".join(
            "none (the example's iteration limit)" if not t else
            f"{t:g} s (" + ("tightfit's --time-limit" if by == "tightfit" else
                            "the runner's: SIGINT, after which tightfit writes the outputs of "
                            "its last iteration") + ")"
            for t, by in sorted(limits, key=lambda x: x[0] or 0)) or "–") + ".",
        "* Load average (1 min) when the rows started: " + (
            ", ".join(f"{x:.1f}" for x in loads) if loads else "–") +
        " (other work on the machine slows every s/it).",
        "",
        "Ratio: final / initial objective. Paper wall time: iterations × s/it of the paper's "
        "Table 1 (an Intel i7-5820K, 6 cores). tightfit's s/it and optimization time count "
        "the design iterations (history.json); the process time adds loading, building the "
        "garment and writing the outputs. *Paper ratio reached*: the optimization time (and "
        "iteration) at which tightfit's objective first fell to the paper's final ratio.",
        "",
        "| row | paper ratio | paper it. | paper s/it | paper wall | ratio | it. | s/it "
        "| optimization | process | paper ratio reached | stop |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in ROWS:
        lines.append("| " + " | ".join([r["model"]] + row_cells(r, measured.get(r["id"]))) + " |")
    lines += ["", "## Summary", "", SUMMARY_BEGIN, "",
              "| row | paper ratio (wall) | tightfit ratio (wall) | paper ratio reached after |",
              "|---|---|---|---|"]
    for r in ROWS:
        m, p = measured.get(r["id"]), r["paper"]
        paper = (f"{fmt(p['final'] / p['initial'])} "
                 f"({seconds_text(p['iterations'] * p['seconds_per_iteration'])})" if p else "–")
        if m is None:
            ours, reached = "not run", ""
        elif "error" in m:
            ours, reached = "failed", ""
        else:
            ours = f"{fmt(m['ratio'])} ({seconds_text(m['runner'].get('wall_seconds'))})"
            reached = (seconds_text(m["reached"]["seconds"]) if m.get("reached")
                       else ("not reached" if p else "–"))
        lines.append(f"| {r['model']} | {paper} | {ours} | {reached} |")
    lines += ["", f"Machine: {'; '.join(machines)}; commit "
              f"{', '.join(c.split()[0][:12] for c in commits)}; "
              f"rows not run: {', '.join(not_run) if not_run else 'none'}.", "", SUMMARY_END, ""]
    return "\n".join(lines)


def summary_block(text):
    """The summary of a results file: the text from SUMMARY_BEGIN to SUMMARY_END."""
    begin, end = text.find(SUMMARY_BEGIN), text.find(SUMMARY_END)
    if begin < 0 or end < begin:
        raise ValueError("no summary markers")
    return text[begin:end + len(SUMMARY_END)]


def copy_summary(results_text, readme):
    """Replaces the summary block of `readme` (between the same markers) by the one of
    `results_text`; the README's results section shows the runner's summary."""
    with open(readme) as f:
        old = f.read()
    try:
        new = old.replace(summary_block(old), summary_block(results_text))
    except ValueError:
        sys.exit(f"table1: {readme} has no {SUMMARY_BEGIN} ... {SUMMARY_END} block")
    with open(readme, "w") as f:
        f.write(new)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary", nargs="?", help="the tightfit binary")
    ap.add_argument("--rows", help="comma-separated row ids (default: all); see --list")
    ap.add_argument("--time-limit", type=float, help="wall-clock budget per row (s)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "results.md"))
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "table1"),
                    help="folder of the runs (default out/table1)")
    ap.add_argument("--report-only", metavar="WORK",
                    help="write the results file from the runs in WORK, running nothing")
    ap.add_argument("--readme", help="file whose summary block gets the new summary (default: "
                    "README.md when --out is docs/results.md, else none; '' for none)")
    ap.add_argument("--list", action="store_true", help="print the row ids and exit")
    a = ap.parse_args(argv)
    if a.list:
        for r in ROWS:
            print(f"{r['id']:22} {r['model']}")
        return 0
    rows = ROW_IDS if not a.rows else [x.strip() for x in a.rows.split(",") if x.strip()]
    unknown = [x for x in rows if x not in ROW_IDS]
    if unknown:
        ap.error(f"unknown row(s) {', '.join(unknown)}; rows: {', '.join(ROW_IDS)}")
    work = a.report_only or a.work
    if not a.report_only:
        if not a.binary:
            ap.error("the tightfit binary is required (or --report-only WORK)")
        binary = os.path.abspath(a.binary)
        for r in ROWS:
            if r["id"] in rows:
                print(f"table1: {r['id']} ...", flush=True)
                rec = run_row(r, binary, work, a.time_limit)
                print(f"table1: {r['id']} exit {rec['returncode']} in "
                      f"{rec['wall_seconds']:.1f} s", flush=True)
    measured = {}
    for r in ROWS:
        if r["id"] in rows:
            measured[r["id"]] = parse_row(r, os.path.join(work, r["id"]))
    command_line = "bench/table1.py " + ("--report-only WORK" if a.report_only else "BIN")
    if a.rows:
        command_line += " --rows " + ",".join(rows)
    if a.time_limit:
        command_line += f" --time-limit {a.time_limit:g}"
    text = report(measured, command_line.strip())
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        f.write(text)
    print(f"table1: wrote {a.out}")
    readme = a.readme if a.readme is not None else (
        os.path.join(ROOT, "README.md")
        if os.path.abspath(a.out) == os.path.join(ROOT, "docs", "results.md") else "")
    if readme:
        copy_summary(text, readme)
        print(f"table1: copied the summary into {readme}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

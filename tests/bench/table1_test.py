#!/usr/bin/env python3
"""Tests of bench/table1.py: the results file from run folders (a finished optimize row, a
graded wetsuit body, a failed row, a row that never reaches the paper's ratio, rows not
run), and the runner's own time limit on a stand-in binary. Runs nothing long."""
import json
import os
import re
import pathlib
import stat
import sys
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import table1  # noqa: E402


def write(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data))


def run_folder(work, row, objectives, seconds_per_iteration, outputs="", runner=None, **extra):
    """A run of `row` whose objective went through `objectives` (one per iteration)."""
    folder = work / row
    write(folder / "runner.json", {"row": row, "returncode": 0, "wall_seconds": 99.0,
                                   "time_limit": None, "machine": "test machine",
                                   "commit": "0123456789abcdef", **(runner or {})})
    iterations = [{"iteration": k, "objective": v, "seconds": k * seconds_per_iteration}
                  for k, v in enumerate(objectives)]
    optimization = {"objective_initial": objectives[0], "objective_final": objectives[-1],
                    "iterations": len(objectives) - 1, "converged": False,
                    "seconds_optimization": (len(objectives) - 1) * seconds_per_iteration,
                    **extra}
    write(folder / outputs / "result.json", {"optimization": optimization})
    write(folder / outputs / "history.json", {"terms": ["stretch"], "iterations": iterations})


def table_rows(text):
    """{model: cells} of the main table."""
    rows = {}
    for line in text.splitlines():
        line = line.strip()
        if not line.startswith("|"):
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line[1:-1])]
        if len(cells) == 12 and cells[0] in {r["model"] for r in table1.ROWS}:
            rows[cells[0]] = cells[1:]
    return rows


class Report(unittest.TestCase):
    def setUp(self):
        self.work = pathlib.Path(self.enterContext(tempfile.TemporaryDirectory()))
        # Tapered: the paper's ratio is 106.952 / 5433.58 = 0.0197; reached at iteration 3.
        run_folder(self.work, "cylinder_tapered", [100.0, 50.0, 10.0, 1.9, 1.5], 0.5,
                   stop_reason="relative decrease below 1e-09 for 3 iterations")
        # The kid's wetsuit is graded: its outputs sit in bodies/child; stop_rule wins.
        run_folder(self.work, "wetsuit_kid", [10.0, 5.0, 4.0], 2.0, outputs="bodies/child",
                   stop_rule="converged: gradient norm below 1e-3 of its initial value",
                   stop_reason="old words")
        # Sphere pressure never reaches the paper's 0.0215.
        run_folder(self.work, "sphere_pressure", [10.0, 5.0, 1.0], 1.0,
                   runner={"stopped_by_runner": True, "returncode": 130}, interrupted=True)
        write(self.work / "pants_stretch" / "runner.json",
              {"row": "pants_stretch", "returncode": 2, "wall_seconds": 3.0,
               "error": "tightfit: scene.json: /body: missing | bad"})
        write(self.work / "pants_sliding" / "runner.json",
              {"row": "pants_sliding", "returncode": None})  # the runner itself was killed
        self.out = self.work / "results.md"
        rows = ("cylinder_tapered,wetsuit_kid,sphere_pressure,pants_stretch,pants_sliding,"
                "mask_pressure")
        self.assertEqual(table1.main(["--report-only", str(self.work), "--rows", rows,
                                      "--out", str(self.out)]), 0)
        self.text = self.out.read_text()
        self.rows = table_rows(self.text)

    def test_a_finished_row(self):
        cells = self.rows["Cylinder tapered (Fig. 3b)"]
        self.assertEqual(cells[:4], ["0.0197", "346", "12.2", "1.2 h"])
        self.assertEqual(cells[4:9], ["0.015", "4", "0.5", "2.0 s", "1.6 min"])
        self.assertEqual(cells[9], "1.5 s (it. 3)")
        self.assertEqual(cells[10], "relative decrease below 1e-09 for 3 iterations")

    def test_a_graded_body_and_the_stop_rule_key(self):
        cells = self.rows["Wetsuit kid (Fig. 9)"]
        self.assertEqual(cells[4:7], ["0.4", "2", "2"])
        self.assertEqual(cells[9], "not reached")
        self.assertEqual(cells[10], "converged: gradient norm below 1e-3 of its initial value")

    def test_a_run_stopped_at_the_time_limit(self):
        cells = self.rows["Sphere pressure (Fig. 5)"]
        self.assertEqual(cells[4], "0.1")
        self.assertEqual(cells[10], "interrupted (stopped at the runner's time limit)")

    def test_a_failed_row_keeps_its_error(self):
        cells = self.rows["Pants stretch (Fig. 1)"]
        self.assertEqual(cells[4], "**failed**")
        self.assertIn("/body: missing \\| bad", cells[10])

    def test_a_row_whose_runner_was_killed_is_failed(self):
        cells = self.rows["Sliding pants (Fig. 7)"]
        self.assertEqual(cells[4], "**failed**")
        self.assertIn("stopped before this row's run ended", cells[10])

    def test_rows_not_run_are_named(self):
        self.assertEqual(self.rows["Mask pressure (Fig. 6)"][4], "not run")
        self.assertEqual(self.rows["Pants shape (Fig. 4)"][4], "not run")
        header = [line for line in self.text.splitlines() if "**not run**" in line][0]
        self.assertIn("mask_pressure", header)
        self.assertIn("stocking_graduated", header)
        self.assertNotIn("cylinder_tapered", header)
        self.assertIn("test machine", self.text)
        self.assertIn("0123456789abcdef", self.text)

    def test_the_summary_is_marked(self):
        begin = self.text.index(table1.SUMMARY_BEGIN)
        summary = self.text[begin:self.text.index(table1.SUMMARY_END)]
        self.assertIn("| Cylinder tapered (Fig. 3b) | 0.0197 (1.2 h) | 0.015 (1.6 min) | 1.5 s |",
                      summary)
        self.assertIn("| Pants stretch (Fig. 1) | 0.0429 (1.6 h) | failed |", summary)


FAKE = """#!/usr/bin/env python3
import json, os, signal, sys, time
if "--help" in sys.argv:
    sys.exit(0)
out = sys.argv[sys.argv.index("--out") + 1]
def stop(*_):
    os.makedirs(out, exist_ok=True)
    json.dump({"optimization": {"objective_initial": 2.0, "objective_final": 1.0,
               "iterations": 1, "seconds_optimization": 1.0, "interrupted": True,
               "stop_reason": "interrupted after iteration 1"}}, open(out + "/result.json", "w"))
    json.dump({"iterations": [{"iteration": 0, "objective": 2.0, "seconds": 0.0},
               {"iteration": 1, "objective": 1.0, "seconds": 1.0}]}, open(out + "/history.json", "w"))
    sys.exit(130)
signal.signal(signal.SIGINT, stop)
time.sleep(60)
"""


class TimeLimit(unittest.TestCase):
    def test_the_runner_interrupts_a_run_past_its_time_limit(self):
        work = pathlib.Path(self.enterContext(tempfile.TemporaryDirectory()))
        binary = work / "fake_tightfit"
        binary.write_text(FAKE)
        binary.chmod(binary.stat().st_mode | stat.S_IEXEC)
        out = work / "results.md"
        self.assertEqual(table1.main([str(binary), "--rows", "cylinder_hourglass",
                                      "--time-limit", "1", "--work", str(work / "runs"),
                                      "--out", str(out)]), 0)
        runner = json.loads((work / "runs" / "cylinder_hourglass" / "runner.json").read_text())
        self.assertTrue(runner["stopped_by_runner"])
        self.assertEqual(runner["time_limit_by"], "runner")
        self.assertLess(runner["wall_seconds"], 30)
        cells = table_rows(out.read_text())["Cylinder hourglass (Fig. 3c)"]
        self.assertEqual(cells[4], "0.5")
        self.assertEqual(cells[10],
                         "interrupted after iteration 1 (stopped at the runner's time limit)")


if __name__ == "__main__":
    unittest.main()

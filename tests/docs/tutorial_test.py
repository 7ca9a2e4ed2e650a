#!/usr/bin/env python3
"""Runs every command of docs/tutorial.md, in order, in a fresh folder, so the tutorial
never goes stale (CTest: Tutorial.Commands).

What it reads from the Markdown:
  * a fenced block whose opening line is preceded by a line `<!-- file: NAME -->`
    (blank lines between them allowed) is a file the reader writes: its text is written
    to NAME (relative to the tutorial's folder) at that point; ```json blocks must parse;
    the marker does not show in the rendered page, so the paragraph before it must name
    the file in backticks (`NAME`);
  * every other fenced ```sh block is commands the reader types, run at that point;
  * `<!-- expect: PATH PATH ... -->` lists files the commands so far must have written;
  * `<!-- check: FILE POINTER ~ VALUE ± TOL -->` (or `<= VALUE`, `>= VALUE`) checks a
    number the text quotes against what the commands wrote: the JSON file FILE at the
    JSON pointer POINTER (`*` stands for every item of an array or member of an object,
    each of which must pass) must be within TOL of VALUE (or at most / at least VALUE);
    VALUE must appear as written in the paragraph before the marker, which quotes it
    (VALUE% is a share the file holds as a fraction, quoted as "VALUE %");
  * other blocks (```text, ```json without a file marker, ...) are only shown.
All blocks run in ONE bash session (`set -euo pipefail`), as a reader would type them in
one terminal. `tightfit` on PATH is the binary given with --tightfit, and TIGHTFIT_HOME
(the folder the tutorial asks the reader to name once) is this source tree, so the
tutorial can copy `$TIGHTFIT_HOME/data/bodies/...`. A command that exits non-zero, a
missing expected file or a JSON file block that does not parse fails the test, naming
the line of docs/tutorial.md.

Usage: tutorial_test.py --tightfit BUILD/tightfit [--tutorial docs/tutorial.md] [--keep DIR]
(--keep runs in DIR, which must not exist yet, and leaves it there:
scripts/tutorial_pictures.sh makes the tutorial's pictures from it.)
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

SOURCE = os.path.realpath(os.path.join(os.path.dirname(__file__), "..", ".."))
FENCE = re.compile(r"^```(\w*)\s*$")
FILE_MARK = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->\s*$")
EXPECT_MARK = re.compile(r"^<!--\s*expect:\s*(.+?)\s*-->\s*$")
CHECK_MARK = re.compile(
    r"^\s*<!--\s*check:\s*(\S+)\s+(\S+)\s+(~|<=|>=)\s+(\S+)(?:\s+±\s*(\S+))?\s*-->\s*$")
# Commands the tutorial must exercise (guards against a parser that finds nothing).
REQUIRED_COMMANDS = ["body", "layout", "simulate", "optimize", "export"]


def parse(path):
    """Returns the steps: ("file", line, name, lang, text), ("sh", line, text) and
    ("expect", line, [paths]), in the order of the document."""
    steps, lines = [], open(path, encoding="utf-8").read().split("\n")
    pending_file, i = None, 0
    while i < len(lines):
        line = lines[i]
        m = FILE_MARK.match(line)
        if m:
            pending_file = (m.group(1), i + 1)
            i += 1
            continue
        m = EXPECT_MARK.match(line)
        if m:
            steps.append(("expect", i + 1, m.group(1).split()))
            i += 1
            continue
        m = CHECK_MARK.match(line)
        if m:
            k = i - 1
            while k >= 0 and (not lines[k].strip() or CHECK_MARK.match(lines[k])):
                k -= 1
            paragraph = []
            while k >= 0 and lines[k].strip() and not lines[k].lstrip().startswith("<!--"):
                paragraph.insert(0, lines[k])
                k -= 1
            quoted = m.group(4)
            text = " ".join(paragraph)
            if quoted not in text and not (quoted.endswith("%") and quoted[:-1] + " %" in text):
                sys.exit(f"{path}:{i + 1}: the paragraph before this check must quote {m.group(4)}")
            if m.group(3) == "~" and not m.group(5):
                sys.exit(f"{path}:{i + 1}: a ~ check needs a tolerance (± TOL)")
            steps.append(("check", i + 1, m.group(1), m.group(2), m.group(3), m.group(4),
                          m.group(5) or "0"))
            i += 1
            continue
        m = FENCE.match(line)
        if m:
            lang, start = m.group(1), i + 1
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            if j == len(lines):
                sys.exit(f"{path}:{start}: code block never closed")
            text = "\n".join(lines[i + 1:j]) + "\n"
            if pending_file:
                # The marker is an HTML comment, invisible to the reader: the paragraph
                # before it must name the file.
                k = pending_file[1] - 2
                while k >= 0 and not lines[k].strip():
                    k -= 1
                paragraph = []
                while k >= 0 and lines[k].strip() and not lines[k].startswith("```"):
                    paragraph.insert(0, lines[k])
                    k -= 1
                if f"`{pending_file[0]}`" not in " ".join(paragraph):
                    sys.exit(f"{path}:{pending_file[1]}: the paragraph before this file block "
                             f"must name it as `{pending_file[0]}` (the marker is not shown)")
                steps.append(("file", start, pending_file[0], lang, text))
            elif lang == "sh":
                steps.append(("sh", start, text))
            pending_file, i = None, j + 1
            continue
        if pending_file and line.strip():
            sys.exit(f"{path}:{pending_file[1]}: a file marker must be followed by a code block")
        i += 1
    return steps


def bash_script(steps, tutorial):
    """One bash script that writes the files, runs the commands and checks the outputs."""
    out = ["set -euo pipefail"]
    for step in steps:
        kind, line = step[0], step[1]
        where = f"{tutorial}:{line}"
        if kind == "file":
            name, text = step[2], step[4]
            if os.path.isabs(name) or ".." in name.split("/"):
                sys.exit(f"{where}: file name must stay in the tutorial's folder: {name}")
            delimiter = "TIGHTFIT_TUTORIAL_EOF"
            if delimiter in text:
                sys.exit(f"{where}: the block contains {delimiter}")
            out.append(f"echo '== {where}: write {name}'")
            out.append(f"mkdir -p \"$(dirname '{name}')\"")
            out.append(f"cat > '{name}' <<'{delimiter}'\n{text}{delimiter}")
        elif kind == "sh":
            out.append(f"echo '== {where}: run'")
            out.append(step[2])
        elif kind == "check":
            args = " ".join(f"'{a}'" for a in (where,) + tuple(step[2:]))
            out.append(f"'{sys.executable}' '{os.path.realpath(__file__)}' --check {args}")
        else:
            for p in step[2]:
                out.append(f"test -e '{p}' || {{ echo '{where}: expected file {p} is missing' >&2; exit 1; }}")
    out.append("echo '== all tutorial commands ran'")
    return "\n".join(out) + "\n"


def values_at(document, pointer):
    """The values at `pointer`, `*` standing for every item or member."""
    nodes = [document]
    for token in pointer.strip("/").split("/"):
        token = token.replace("~1", "/").replace("~0", "~")
        nxt = []
        for n in nodes:
            if token == "*":
                nxt.extend(n.values() if isinstance(n, dict) else n)
            elif isinstance(n, list):
                nxt.append(n[int(token)])
            else:
                nxt.append(n[token])
        nodes = nxt
    return nodes


def check(where, path, pointer, op, value, tol="0"):
    """Exits 1 (naming the tutorial's line) when a quoted number disagrees with the file."""
    try:
        with open(path) as f:
            found = values_at(json.load(f), pointer)
    except (OSError, ValueError, KeyError, IndexError, TypeError) as e:
        sys.exit(f"{where}: cannot read {path} {pointer}: {e}")
    if not found:
        sys.exit(f"{where}: {path} has nothing at {pointer}")
    percent = value.endswith("%")  # a share quoted in percent, a fraction in the file
    v, t = float(value.rstrip("%")), float(tol.rstrip("%"))
    for x in found:
        x = 100.0 * x if percent else x
        ok = abs(x - v) <= t if op == "~" else (x <= v if op == "<=" else x >= v)
        if not ok:
            sys.exit(f"{where}: the text quotes {value}"
                     f"{' ± ' + tol if op == '~' else ''} ({op}), but {path} {pointer} is {x}")
    return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--check":
        return check(*sys.argv[2:8])
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tightfit", required=True, help="the tightfit binary")
    ap.add_argument("--tutorial", default=os.path.join(SOURCE, "docs", "tutorial.md"))
    ap.add_argument("--keep", help="run in this folder (must not exist) and keep it")
    args = ap.parse_args()

    tightfit = os.path.realpath(args.tightfit)
    if not os.access(tightfit, os.X_OK):
        sys.exit(f"not an executable: {tightfit}")
    tutorial = os.path.realpath(args.tutorial)
    steps = parse(tutorial)
    sh_text = "".join(s[2] for s in steps if s[0] == "sh")
    missing = [c for c in REQUIRED_COMMANDS if not re.search(rf"^\s*tightfit {c}\b", sh_text, re.M)]
    if missing:
        sys.exit(f"{tutorial}: no ```sh block runs tightfit {', '.join(missing)}")
    for s in steps:
        if s[0] == "file" and s[3] == "json":
            try:
                json.loads(s[4])
            except json.JSONDecodeError as e:
                sys.exit(f"{tutorial}:{s[1]}: {s[2]} is not valid JSON: {e}")

    if args.keep:
        os.makedirs(args.keep)  # fails if it exists: a fresh folder, like the test's
        work, cleanup = os.path.realpath(args.keep), None
    else:
        cleanup = tempfile.TemporaryDirectory(prefix="tightfit-tutorial-")
        work = cleanup.name
    try:
        run_dir = os.path.join(work, "calf")  # the reader's own project folder
        bin_dir = os.path.join(work, "bin")
        os.makedirs(run_dir)
        os.makedirs(bin_dir)
        os.symlink(tightfit, os.path.join(bin_dir, "tightfit"))
        env = dict(os.environ)
        env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
        env["TIGHTFIT_HOME"] = SOURCE
        shown = os.path.relpath(tutorial, SOURCE) if tutorial.startswith(SOURCE + os.sep) else tutorial
        script = bash_script(steps, shown)
        with open(os.path.join(work, "tutorial.sh"), "w") as f:
            f.write(script)
        start = time.monotonic()
        result = subprocess.run(["bash", os.path.join(work, "tutorial.sh")], cwd=run_dir, env=env)
        elapsed = time.monotonic() - start
        blocks = sum(1 for s in steps if s[0] == "sh")
        files = sum(1 for s in steps if s[0] == "file")
        if result.returncode != 0:
            print(f"FAILED: the tutorial's commands stopped with exit code {result.returncode} "
                  f"after {elapsed:.1f} s (see the last '==' line above)", file=sys.stderr)
            return 1
        checks = sum(1 for s in steps if s[0] == "check")
        print(f"tutorial OK: {files} files written, {blocks} command blocks run, {checks} quoted "
              f"numbers checked, in {elapsed:.1f} s")
        return 0
    finally:
        if cleanup:
            cleanup.cleanup()


if __name__ == "__main__":
    sys.exit(main())

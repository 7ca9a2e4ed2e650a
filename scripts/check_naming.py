#!/usr/bin/env python3
"""Naming check: clang-tidy's readability-identifier-naming (rules in .clang-tidy, the
text in CONTRIBUTING.md) over every translation unit of src/ in a configured build.

usage: scripts/check_naming.py [BUILD_DIR] [--jobs N] [FILE...]
  BUILD_DIR  a CMake build with compile_commands.json (default build/release)
  FILE       check only these sources (default: every src/**/*.cpp in the build)

The build's compile commands are GCC's: their precompiled-header flags are removed, as
are the warning flags clang does not know, so clang-tidy parses each file as the
compiler saw it. Headers are checked through the sources that include them
(HeaderFilterRegex), each diagnostic reported once. Exits 1 and lists every name that
breaks a rule, 0 when there is none.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GCC_ONLY = re.compile(r"\s(-include \S*cmake_pch\.hxx|-Winvalid-pch|-Werror|-frounding-math)(?=\s)")
DIAGNOSTIC = re.compile(r"^(/\S+?):(\d+):(\d+): (?:warning|error): (.*)\[readability-identifier-naming")


def main(argv):
    build = os.path.join(ROOT, "build", "release")
    jobs = os.cpu_count() or 2
    files = []
    args = iter(argv)
    for a in args:
        if a == "--jobs":
            jobs = int(next(args))
        elif os.path.isdir(a) and not files:
            build = a
        else:
            files.append(os.path.abspath(a))
    db_file = os.path.join(build, "compile_commands.json")
    if not os.path.exists(db_file):
        sys.exit(f"check_naming: {db_file} not found: configure the build first (make build)")
    with open(db_file) as f:
        db = json.load(f)
    src = os.path.join(ROOT, "src") + os.sep
    entries = []
    for e in db:
        path = os.path.abspath(os.path.join(e["directory"], e["file"]))
        if not path.startswith(src) or (files and path not in files):
            continue
        e = dict(e)
        e["command"] = GCC_ONLY.sub(" ", e["command"] + " ")
        entries.append(e)
    if not entries:
        sys.exit("check_naming: no source of src/ in " + db_file)

    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "compile_commands.json"), "w") as f:
            json.dump(entries, f)

        def tidy(entry):
            r = subprocess.run(["clang-tidy", "--quiet", "-p", tmp, entry["file"]],
                               capture_output=True, text=True)
            found = set()
            for line in r.stdout.splitlines():
                m = DIAGNOSTIC.match(line)
                if m:
                    found.add((os.path.relpath(m.group(1), ROOT), int(m.group(2)), m.group(4).strip()))
            if r.returncode != 0 and not found:
                found.add((os.path.relpath(entry["file"], ROOT), 0,
                           "clang-tidy failed: " + (r.stderr.strip() or r.stdout.strip())[-400:]))
            return found

        with ThreadPoolExecutor(max_workers=jobs) as pool:
            problems = set().union(*pool.map(tidy, entries))
    for path, line, message in sorted(problems):
        print(f"{path}:{line}: {message}")
    print(f"check_naming: {len(entries)} sources, {len(problems)} names breaking the rules "
          "of .clang-tidy (CONTRIBUTING.md, 'Files and names')")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

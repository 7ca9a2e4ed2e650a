#!/usr/bin/env python3
"""Naming check: clang-tidy's readability-identifier-naming (rules in .clang-tidy, the
text in CONTRIBUTING.md) over every source of src/ in a configured build.

usage: scripts/check_naming.py [BUILD_DIR] [--jobs N] [--group N] [FILE...]
  BUILD_DIR  a CMake build with compile_commands.json (default build/release)
  --group N  sources per clang-tidy run (default 48; 1: each source alone)
  FILE       check only these sources (default: every src/**/*.cpp in the build)

Parsing the headers (Eigen, CGAL, JSON) is most of clang-tidy's time, so sources compiled
with the same flags are checked N at a time through a generated file that includes them
(headers and included sources are checked alike: HeaderFilterRegex). A unity build's
batch files (the library layers compile that way) count as the sources they include. A
group whose sources do not compile together (two files' internal helpers of the same name) is
checked again source by source, so every source is checked in full either way. The
build's compile commands are GCC's: their precompiled-header flags are removed, as are
the flags clang does not know. Each diagnostic is reported once. Exits 1 and lists every
name that breaks a rule, 0 when there is none.
"""
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GCC_ONLY = re.compile(r"\s(-include \S*cmake_pch\.hxx|-Winvalid-pch|-Werror|-frounding-math)(?=\s)")
DIAGNOSTIC = re.compile(
    r"^(/\S+?):(\d+):(\d+): (?:warning|error): (.*)\[readability-identifier-naming")
COMPILE_ERROR = "[clang-diagnostic-error]"


def flags_of(command):
    """The compile command without its output and source: the key of a group."""
    args = shlex.split(command)
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
        elif a in ("-o", "-c"):
            skip = True
        else:
            out.append(a)
    return " ".join(shlex.quote(a) for a in out)


UNITY_INCLUDE = re.compile(r'^#include "(/[^"]+)"$', re.M)


def unity_members(path):
    """The sources a CMake unity-build file (Unity/unity_N_cxx.cxx) includes, else []."""
    if os.sep + "Unity" + os.sep not in path or not path.endswith(".cxx"):
        return []
    with open(path) as f:
        return [os.path.abspath(m) for m in UNITY_INCLUDE.findall(f.read())]


def run_tidy(db_dir, source):
    r = subprocess.run(["clang-tidy", "--quiet", "--config-file=" + os.path.join(ROOT, ".clang-tidy"),
                        "-p", db_dir, source],
                       capture_output=True, text=True)
    found = set()
    for line in r.stdout.splitlines():
        m = DIAGNOSTIC.match(line)
        if m:
            found.add((os.path.relpath(m.group(1), ROOT), int(m.group(2)), m.group(4).strip()))
    compiled = COMPILE_ERROR not in r.stdout
    return found, compiled, r


def main(argv):
    build = os.path.join(ROOT, "build", "release")
    jobs = os.cpu_count() or 2
    group = 48
    files = []
    args = iter(argv)
    for a in args:
        if a == "--jobs":
            jobs = int(next(args))
        elif a == "--group":
            group = max(1, int(next(args)))
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
    by_flags, key_of = {}, {}
    for e in db:
        path = os.path.abspath(os.path.join(e["directory"], e["file"]))
        command = GCC_ONLY.sub(" ", e["command"] + " ")
        key = (e["directory"], flags_of(command))
        for member in unity_members(path) or [path]:
            if not member.startswith(src) or (files and member not in files):
                continue
            by_flags.setdefault(key, []).append(member)
            key_of[member] = key
    if not by_flags:
        sys.exit("check_naming: no source of src/ in " + db_file)

    with tempfile.TemporaryDirectory() as tmp:
        entries, units = [], []
        for (directory, flags), paths in sorted(by_flags.items()):
            paths.sort()
            for i in range(0, len(paths), group):
                members = paths[i:i + group]
                if len(members) == 1:
                    unit = members[0]
                else:
                    unit = os.path.join(tmp, f"group_{len(units)}.cpp")
                    with open(unit, "w") as f:
                        f.writelines(f'#include "{p}"\n' for p in members)
                units.append((unit, members))
                for p in set([unit] + members):
                    entries.append({"directory": directory, "file": p,
                                    "command": f"{flags} -c {shlex.quote(p)}"})
        with open(os.path.join(tmp, "compile_commands.json"), "w") as f:
            json.dump(entries, f)

        fallbacks = []

        lock = threading.Lock()

        def write_group(members):
            """A new group file, added to the compilation database (replaced atomically:
            clang-tidy runs of other groups read it meanwhile)."""
            with lock:
                unit = os.path.join(tmp, f"split_{len(entries)}.cpp")
                with open(unit, "w") as f:
                    f.writelines(f'#include "{p}"\n' for p in members)
                directory, flags = key_of[members[0]]
                entries.append({"directory": directory, "file": unit,
                                "command": f"{flags} -c {shlex.quote(unit)}"})
                db_tmp = os.path.join(tmp, "compile_commands.json.new")
                with open(db_tmp, "w") as f:
                    json.dump(entries, f)
                os.replace(db_tmp, os.path.join(tmp, "compile_commands.json"))
            return unit

        def check(unit_members):
            unit, members = unit_members
            found, compiled, r = run_tidy(tmp, unit)
            if compiled:
                return found
            if len(members) == 1:
                return found | {(os.path.relpath(unit, ROOT), 0, "does not compile under clang-tidy: "
                                 + (r.stdout.strip() or r.stderr.strip())[-400:])}
            # The group does not compile together (two files' internal helpers of the same
            # name): its halves are checked apart, down to single sources.
            with lock:
                fallbacks.append(len(members))
            halves = [members[:len(members) // 2], members[len(members) // 2:]]
            found = set()
            for half in halves:
                found |= check((half[0] if len(half) == 1 else write_group(half), half))
            return found

        # Largest groups first, so that the last ones to finish are short.
        units.sort(key=lambda unit: -len(unit[1]))
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            problems = set().union(*pool.map(check, units))
    sources = sum(len(m) for _, m in units)
    for path, line, message in sorted(problems):
        print(f"{path}:{line}: {message}")
    print(f"check_naming: {sources} sources in {len(units)} groups ({len(fallbacks)} split because "
          f"their sources do not compile together), {len(problems)} "
          "names breaking the rules of .clang-tidy (CONTRIBUTING.md, 'Files and names')")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/env python3
"""Tests of scripts/check_docs.py on small trees written to a temporary folder
(CTest: Docs.CheckDocsFindsWhatItShould): every pattern it must catch is caught, with
the file and line, and the look-alikes it must leave alone (seam names, CSS colours,
ordinary uses of the words, code blocks) pass.

Usage: check_docs_test.py
"""
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "check_docs.py")

# Strings assembled at run time, so that this file itself holds no marker.
SESSION = "sess" + "ion 12"
ISSUE = "iss" + "ue 7"
ISSUE_HASH = "iss" + "ue #7"
ISSUE_TITLE = "iss" + "ue \"Forward simulation\""
PR = "(" + "#31)"
TRIED = "tri" + "ed twice and not " + "kept"
OLD_DESIGN = "DES" + "IGN.md"
HASH = "c0f3" + "21c"

CLEAN = {
    "README.md": "# Top\n\nSee [the guide](docs/guide.md#first-part) and [code](src).\n"
                 "![picture](docs/img/a.png)\n",
    "docs/guide.md": "# Guide\n\n## First part\n\nSeam `A/B#2` and colour #999; an issue of "
                     "scale; the session ends.\n\n[back](../README.md#top)\n"
                     "```sh\n[not a link](missing.md)\n```\n"
                     "Inline `[not a link](missing.md)` too.\n",
    "docs/img/a.png": "",
    "src/a.cpp": "// seam \"left/right#3\", stroke #000, one session per run\nint a;\n",
}


def write(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


def run(files):
    with tempfile.TemporaryDirectory() as root:
        write(root, files)
        done = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
        return done.returncode, done.stdout


def expect(condition, message, failures):
    if not condition:
        failures.append(message)


def main():
    failures = []
    code, out = run(CLEAN)
    expect(code == 0, f"a clean tree fails:\n{out}", failures)

    planted = {
        "src/b.hpp": f"/// Made in {SESSION}.\n",
        "tests/c.cpp": f"// See {ISSUE}.\n",
        "scripts/d.py": f"# From {ISSUE_HASH}\n",
        "bench/e.cpp": f"// {ISSUE_TITLE}, item 2\n",
        "examples/f.json": f'{{"description": "Faster {PR}"}}\n',
        "docs/g.md": f"# G\n\nWe {TRIED}.\n",
        "CMakeLists.txt": f"# see {OLD_DESIGN}\n",
        "CONTRIBUTING.md": f"# C\n\nMeasured at {HASH}.\n",
    }
    code, out = run({**CLEAN, **planted})
    expect(code == 1, f"planted markers pass:\n{out}", failures)
    for rel in planted:
        expect(f"{rel}:" in out, f"{rel}: its marker is not reported:\n{out}", failures)

    broken = {
        "docs/h.md": "# H\n\n[gone](nowhere.md) [bad anchor](guide.md#no-such-part) "
                     "[self](#h) [self bad](#nothing)\n\n[ref]: ../missing/file.txt\n",
    }
    code, out = run({**CLEAN, **broken})
    expect(code == 1, f"broken links pass:\n{out}", failures)
    for what in ["'nowhere.md'", "'guide.md#no-such-part'", "'#nothing'",
                 "'../missing/file.txt'"]:
        expect(what in out, f"broken link {what} is not reported:\n{out}", failures)
    expect("'#h'" not in out, f"a valid anchor in the same file is reported:\n{out}", failures)

    begin, end = "<!-" + "- table1-summary:begin -->", "<!-" + "- table1-summary:end -->"
    results = {"docs/results.md": f"# R\n\n{begin}\n| a | 0.5 |\ncommit {HASH}\n{end}\n"}
    same_summary = {"README.md": CLEAN["README.md"] +
                    f"\n{begin}\n| a | 0.5 |\ncommit {HASH}\n{end}\n"}
    code, out = run({**CLEAN, **results, **same_summary})
    expect(code == 0, f"a README holding the results summary (with its commit) fails:\n{out}",
           failures)
    stale_summary = {"README.md": CLEAN["README.md"] +
                     f"\n{begin}\n| a | 0.4 |\ncommit {HASH}\n{end}\n"}
    code, out = run({**CLEAN, **results, **stale_summary})
    expect(code == 1 and "results summary differs" in out,
           f"a README whose summary differs from docs/results.md passes:\n{out}", failures)

    if failures:
        print("\n".join(failures))
        return 1
    print("check_docs_test: all cases behave")
    return 0


if __name__ == "__main__":
    sys.exit(main())

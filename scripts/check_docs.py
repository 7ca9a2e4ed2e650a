#!/usr/bin/env python3
"""Checks the repository's documents and sources for two things (ctest
Docs.NoHistoryAndLinksResolve):

1. No development history. Git keeps the history and CHANGELOG.md says what changed for
   users, so no source, document, example or script may carry a development-log marker
   or an issue reference. The patterns (case-insensitive, whole words):
     * the word "session" or "sessions" followed by a number;
     * the word "issue" or "issues" followed by a number, "#" and a number, or a quoted
       issue title;
     * a pull-request style marker: "#" and a number in parentheses;
     * "tried", up to 40 characters without a full stop, then "and not kept" (a diary
       of experiments);
     * the old name of the design notes, in capitals, with the .md suffix (they are
       docs/design.md now);
     * in Markdown documents only: a commit hash, i.e. a word of 7 to 40 hexadecimal
       digits holding both a digit and a letter a-f — except in the two pages of
       measured figures (MEASURED_PAGES), which name the commit they were measured at.
   Seam names such as "A/B#2" and CSS colours such as "#999" do not match: a bare "#"
   and a number is not a marker.

2. Every relative link resolves. In README.md, CONTRIBUTING.md, CHANGELOG.md and
   docs/**/*.md, every Markdown link and image `[text](target)` and every reference
   definition `[name]: target` outside code blocks and code spans whose target is not
   an absolute URL must name an existing file or folder (relative to the document), and
   an anchor `#name` in a link to a Markdown file (or in the same document) must be the
   GitHub anchor of one of its headings.

   The README's results summary (between the markers of SUMMARY_BEGIN and SUMMARY_END)
   must be the copy of docs/results.md's, which bench/table1.py writes.

   PENDING lists documents written on other branches that are linked before they land.
   A link to a pending document that does not exist yet is reported but does not fail;
   once the document exists the entry must be removed (the check fails until it is), so
   the list can only shrink.

Usage: scripts/check_docs.py [SOURCE_DIR]   (default: the folder above this script)
Exit status 0 when clean, 1 with one line per finding (FILE:LINE: what).
"""
import os
import re
import sys

# Folders (relative to the source folder) whose text files are checked for history, and
# top-level files checked too.
HISTORY_ROOTS = ["src", "tests", "docs", "examples", "scripts", "bench", "cmake", "fuzz",
                 "schema", "report", ".ci"]
HISTORY_FILES = ["README.md", "CONTRIBUTING.md", "CHANGELOG.md", "CMakeLists.txt",
                 "Makefile"]
# Not checked: third-party and generated trees, and fuzzing inputs (arbitrary bytes).
SKIP_DIRS = {"node_modules", "fuzz_regressions", "__pycache__", ".git"}
TEXT_SUFFIXES = {".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".md", ".json", ".cmake",
                 ".txt", ".js", ".mjs", ".html", ".css", ".supp", ".in", ".yml", ".yaml"}
TEXT_NAMES = {"CMakeLists.txt", "Makefile", "run"}
SKIP_FILES = {"package-lock.json"}  # npm's lock file holds integrity hashes

HISTORY_PATTERNS = [
    (re.compile(r"\bsessions?\s+\d+", re.IGNORECASE), "development-log marker"),
    (re.compile(r"\bissues?\s+(?:#\s*)?\d+", re.IGNORECASE), "issue number"),
    (re.compile(r"\bissues?\s+[\"“]", re.IGNORECASE), "issue reference by title"),
    (re.compile(r"\(#\d+\)"), "pull-request marker"),
    (re.compile(r"\btried\b[^.\n]{0,40}\band not kept\b", re.IGNORECASE),
     "diary of experiments"),
    (re.compile(r"\bDESIGN\.md\b"), "old name of docs/design.md"),
]
# Pages of current measured figures: each figure names the commit of the binary.
MEASURED_PAGES = {"docs/benchmarks.md", "docs/results.md"}
COMMIT_HASH = re.compile(r"(?<![\w#./-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}(?![\w/-])")

# The results page the Table 1 runner writes, and the markers of its summary, which the
# README holds a copy of (bench/table1.py copies it).
RESULTS_PAGE = "docs/results.md"
SUMMARY_BEGIN = "<!-- table1-summary:begin -->"
SUMMARY_END = "<!-- table1-summary:end -->"

# Documents whose links are checked: these files and every .md under docs/.
LINK_FILES = ["README.md", "CONTRIBUTING.md", "CHANGELOG.md"]
LINK_ROOT = "docs"
# Documents of other branches linked before they land (see the module comment).
PENDING = set()

HTML_ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
URL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def text_files(root):
    """Yields (absolute path, path relative to root) of every checked text file."""
    for name in HISTORY_FILES:
        path = os.path.join(root, name)
        if os.path.isfile(path):
            yield path, name
    for top in HISTORY_ROOTS:
        base = os.path.join(root, top)
        for folder, dirs, files in os.walk(base):
            dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
            for name in sorted(files):
                suffix = os.path.splitext(name)[1]
                if name in SKIP_FILES or (suffix not in TEXT_SUFFIXES and name not in TEXT_NAMES):
                    continue
                path = os.path.join(folder, name)
                yield path, os.path.relpath(path, root)


def read_lines(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read().split("\n")


def history_findings(root):
    findings = []
    for path, rel in text_files(root):
        markdown = rel.endswith(".md") and rel not in MEASURED_PAGES
        lines = read_lines(path)
        summary = summary_line_numbers(lines) if rel == "README.md" else set()
        for number, line in enumerate(lines, 1):
            for pattern, what in HISTORY_PATTERNS:
                m = pattern.search(line)
                if m:
                    findings.append(f"{rel}:{number}: {what}: '{m.group(0)}'")
            if markdown and number not in summary:
                m = COMMIT_HASH.search(line)
                if m:
                    findings.append(f"{rel}:{number}: commit hash: '{m.group(0)}'")
    return findings


def summary_line_numbers(lines):
    """Line numbers (1-based) of the results summary block: the README's copy of the
    measured figures of docs/results.md, which names their commit."""
    numbers, inside = set(), False
    for number, line in enumerate(lines, 1):
        if line.strip() == SUMMARY_BEGIN:
            inside = True
        if inside:
            numbers.add(number)
        if line.strip() == SUMMARY_END:
            inside = False
    return numbers


def summary_findings(root):
    """The README's results summary must be the one bench/table1.py wrote into
    docs/results.md (the runner copies it; nobody edits it by hand)."""
    readme, results = os.path.join(root, "README.md"), os.path.join(root, RESULTS_PAGE)
    if not os.path.exists(results):
        return []
    def block(path):
        lines = read_lines(path)
        numbers = summary_line_numbers(lines)
        return [lines[n - 1] for n in sorted(numbers)]
    expected, actual = block(results), block(readme)
    if not expected:
        return [f"{RESULTS_PAGE}: no {SUMMARY_BEGIN} ... {SUMMARY_END} block"]
    if actual != expected:
        return [f"README.md: its results summary differs from the one in {RESULTS_PAGE}: "
                "rerun bench/table1.py (or bench/table1.py --report-only WORK), which copies it"]
    return []


def prose_lines(lines):
    """Yields (line number, line without code spans) of the lines outside fenced code
    blocks."""
    fenced = None
    for number, line in enumerate(lines, 1):
        m = FENCE.match(line)
        if m:
            if fenced is None:
                fenced = m.group(1)
            elif m.group(1) == fenced:
                fenced = None
            continue
        if fenced is None:
            yield number, CODE_SPAN.sub("", line)


def slug(heading):
    """GitHub's anchor of a heading: lower case, markup and punctuation dropped, spaces
    turned into hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # links: their text
    text = text.replace("`", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    """The anchors of every heading of a Markdown file (duplicates numbered -1, -2, …) and
    of every explicit HTML anchor (<a id="…"> or <a name="…">)."""
    if path not in cache:
        seen, result = {}, set()
        for _, line in prose_lines(read_lines(path)):
            result.update(HTML_ANCHOR.findall(line))
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            result.add(base if count == 0 else f"{base}-{count}")
        cache[path] = result
    return cache[path]


def link_documents(root):
    for name in LINK_FILES:
        path = os.path.join(root, name)
        if os.path.isfile(path):
            yield path
    for folder, dirs, files in os.walk(os.path.join(root, LINK_ROOT)):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(folder, name)


def link_targets(lines):
    for number, line in prose_lines(lines):
        for m in INLINE_LINK.finditer(line):
            yield number, m.group(1)
        m = REFERENCE_DEF.match(line)
        if m:
            yield number, m.group(1)


def link_findings(root):
    findings, notes = [], []
    for doc in link_documents(root):
        rel_doc = os.path.relpath(doc, root)
        for number, target in link_targets(read_lines(doc)):
            if URL.match(target):
                continue
            where = f"{rel_doc}:{number}"
            file_part, _, anchor = target.partition("#")
            path = os.path.normpath(os.path.join(os.path.dirname(doc), file_part)) if file_part else doc
            rel_target = os.path.relpath(path, root)
            if not os.path.exists(path):
                if rel_target in PENDING:
                    notes.append(f"{where}: link to {rel_target}, pending on another branch")
                else:
                    findings.append(f"{where}: broken link '{target}': no {rel_target}")
                continue
            if anchor and path.endswith(".md") and anchor not in anchors(path):
                findings.append(f"{where}: broken link '{target}': no heading "
                                f"'#{anchor}' in {rel_target}")
    for pending in sorted(PENDING):
        if os.path.exists(os.path.join(root, pending)):
            findings.append(f"scripts/check_docs.py: {pending} exists now: remove it from "
                            "PENDING so that its links are checked like any other")
    return findings, notes


def main(argv):
    root = os.path.realpath(argv[1] if len(argv) > 1 else
                            os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    findings = history_findings(root)
    links, notes = link_findings(root)
    findings += links
    findings += summary_findings(root)
    for note in notes:
        print(f"note: {note}")
    for finding in findings:
        print(finding)
    if findings:
        print(f"check_docs: {len(findings)} finding(s): development history or broken links")
        return 1
    print("check_docs: no development history, every relative link resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

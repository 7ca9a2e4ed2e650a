#!/usr/bin/env python3
"""Size rule for the C++ sources under src/: a file has at most 500 lines and a function
(its definition, from the line of its name to its closing brace) at most 120.

The allow-list (scripts/size_allowlist.txt) names the current offenders, one per line:
`PATH` for a file, `PATH:FUNCTION` for a function (FUNCTION qualified as written or by
its enclosing class, e.g. `src/tightfit/design/pattern_optimizer.cpp:PatternOptimizer::run`).
The list may only shrink: the check fails on an offender that is not listed and on a
listed entry that no longer exceeds its limit (delete the line) or no longer exists.
Prints the problems and exits 1; exits 0 when there is none.

Usage: scripts/check_sizes.py [SOURCE_ROOT] [--list]
  --list  print every file and function over the limits (to seed the allow-list)."""
import pathlib
import re
import sys

MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 120

_KEYWORDS_NOT_FUNCTIONS = {"namespace", "class", "struct", "union", "enum"}
_CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype",
            "alignof", "noexcept", "requires", "static_assert"}


def strip_code(text):
    """Replaces comments, string and character literals (raw strings too) by spaces,
    keeping every newline, so that braces and parentheses in them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
                                                         or text[i - 1] in "uUL8"):
            m = re.match(r'R"([^()\\ ]{0,16})\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            end = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:end]))
            i = end
        elif c in "\"'":
            # A digit separator (1'000'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and re.match(r"[0-9a-fA-F]", text[i + 1:i + 2] or " ") \
                    and re.search(r"\b0[xXbB]?[0-9a-fA-F']*$|\b\d[0-9']*$", text[:i]):
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else c)
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


_TOKEN = re.compile(r"::|->|[A-Za-z_]\w*|\d[\w.']*|\S")


def tokens(code):
    """(token, line) pairs of stripped code; preprocessor lines are left out."""
    out = []
    for number, line in enumerate(code.split("\n"), 1):
        if line.lstrip().startswith("#"):
            continue
        out.extend((m.group(0), number) for m in _TOKEN.finditer(line))
    return out


def _matching(toks, i, open_, close):
    depth = 0
    for j in range(i, len(toks)):
        if toks[j][0] == open_:
            depth += 1
        elif toks[j][0] == close:
            depth -= 1
            if depth == 0:
                return j
    return len(toks) - 1


def _without_template(words):
    """`words` without a leading `template <...>`."""
    if words[:2] != ["template", "<"]:
        return words
    depth = 0
    for k, w in enumerate(words):
        depth += (w == "<") - (w == ">")
        if depth == 0 and k > 0:
            return words[k + 1:]
    return []


def _function_name(header):
    """The (qualified) name of the function whose definition a declaration header starts,
    or None when the header is not a function's (an initializer, a lambda, an enum, ...)."""
    words = _without_template([t for t, _ in header])
    if not words or words[0] in _KEYWORDS_NOT_FUNCTIONS or words[0] in _CONTROL:
        return None
    for k, w in enumerate(words):
        if w != "(":
            continue
        if "=" in words[:k] and "operator" not in words[:k]:
            return None  # a variable initialized by a lambda or a braced list
        if k >= 1 and words[k - 1] == "operator":  # operator()
            start, name = k - 1, "operator()"
        elif "operator" in words[:k]:
            start = words.index("operator")
            name = "operator" + "".join(words[start + 1:k])
        else:
            start, name = k - 1, words[k - 1] if k >= 1 else ""
            if not re.match(r"[A-Za-z_]\w*$", name) or name in _CONTROL:
                return None
        if start >= 1 and words[start - 1] == "~":
            start -= 1
            name = "~" + name
        while start >= 2 and words[start - 1] == "::" and re.match(r"[A-Za-z_]\w*$", words[start - 2]):
            start -= 2
            name = words[start] + "::" + name
        return name
    return None


def functions(text):
    """(qualified name, first line, last line) of every function defined in C++ text."""
    toks = tokens(strip_code(text))
    found = []

    def scan(i, end, scope):
        header = []
        while i < end:
            t, line = toks[i]
            if t == ";":
                header = []
            elif t == "}":
                header = []
            elif t == ":" and header and header[-1][0] in ("public", "private", "protected"):
                header = []
            elif t == "{":
                close = _matching(toks, i, "{", "}")
                words = [w for w, _ in header]
                # A braced list inside parentheses (a default argument `= {}`, a member
                # initializer `x_(a, {})`) or a braced member initializer `x_{a}` belongs
                # to the header.
                open_parens = words.count("(") - words.count(")")
                member_init = (len(header) >= 2 and re.match(r"[A-Za-z_]\w*$", header[-1][0])
                               and header[-2][0] in (",", ":") and ")" in words and ":" in words)
                if open_parens > 0 or member_init:
                    header.extend(toks[i:close + 1])
                    i = close + 1
                    continue
                if words and (words[0] == "namespace" or
                              (words[0] == "extern" and "(" not in words)):
                    scan(i + 1, close, scope)
                    header = []
                    i = close + 1
                    continue
                kind = _without_template(words)
                if kind and kind[0] in ("class", "struct", "union") and "(" not in kind \
                        and "=" not in kind:
                    name = next((w for w in kind[1:] if re.match(r"[A-Za-z_]\w*$", w)
                                 and w not in ("final", "alignas")), "")
                    scan(i + 1, close, scope + [name])
                    header = []
                    i = close + 1
                    continue
                name = _function_name(header) if header else None
                if name:
                    last = name.split("::")[-1]
                    name_line = next((ln for w, ln in header if w == last.lstrip("~")), header[0][1])
                    found.append(("::".join(scope + [name]), name_line, toks[close][1]))
                elif header and kind and kind[0] not in _KEYWORDS_NOT_FUNCTIONS and \
                        any(w == "[" for w, _ in toks[i:close]):
                    # A variable initialized with lambdas (a command's registration): its
                    # code counts like a function's, under the variable's name.
                    before = words[:words.index("=")] if "=" in words else words
                    ids = [w for w in before if re.match(r"[A-Za-z_]\w*$", w)]
                    if ids:
                        found.append(("::".join(scope + [ids[-1]]), header[0][1], toks[close][1]))
                header = []
                i = close + 1
                continue
            else:
                header.append((t, line))
            i += 1

    scan(0, len(toks), [])
    return found


def measure(root):
    """Every file and function over the limits: {entry: lines}."""
    over = {}
    for path in sorted((root / "src").rglob("*.[ch]pp")):
        rel = path.relative_to(root).as_posix()
        text = path.read_text()
        lines = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
        if lines > MAX_FILE_LINES:
            over[rel] = lines
        for name, first, last in functions(text):
            length = last - first + 1
            if length > MAX_FUNCTION_LINES:
                key = f"{rel}:{name}"
                over[key] = max(over.get(key, 0), length)
    return over


def read_allowlist(file):
    entries = []
    for line in file.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            entries.append(line)
    return entries


def check(root, allowlist):
    over = measure(root)
    problems = []
    listed = set(allowlist)
    for entry, lines in sorted(over.items()):
        if entry not in listed:
            limit = MAX_FUNCTION_LINES if ":" in entry else MAX_FILE_LINES
            problems.append(f"{entry}: {lines} lines (limit {limit}); shorten it")
    for entry in allowlist:
        if entry not in over:
            problems.append(f"{entry}: allow-listed but within its limit now (or gone): "
                            "delete it from scripts/size_allowlist.txt")
    return over, problems


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    root = pathlib.Path(args[0] if args else pathlib.Path(__file__).resolve().parent.parent)
    if "--list" in argv:
        for entry, lines in sorted(measure(root).items()):
            print(f"{entry}  # {lines} lines")
        return 0
    allowlist = read_allowlist(root / "scripts" / "size_allowlist.txt")
    over, problems = check(root, allowlist)
    if problems:
        print("\n".join(problems))
        return 1
    print(f"sizes: files <= {MAX_FILE_LINES} lines, functions <= {MAX_FUNCTION_LINES} lines; "
          f"{len(allowlist)} allow-listed offenders")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

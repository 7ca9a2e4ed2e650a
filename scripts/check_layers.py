#!/usr/bin/env python3
"""The layer rule: a file of layer L (src/tightfit/L/) includes only headers of L and of
the layers L depends on, directly or not (the DEPS of tightfit_add_layer in
CMakeLists.txt). Prints every include that breaks it and exits 1; exits 0 when none does.
Usage: scripts/check_layers.py [SOURCE_ROOT]"""
import pathlib, re, sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
cmake = (root / "CMakeLists.txt").read_text()
deps = {m.group(1): set(re.findall(r"tightfit_(\w+)", m.group(2)))
        for m in re.finditer(r"tightfit_add_layer\((\w+)\s+DEPS([^)]*)\)", cmake)}
def below(layer, seen=None):
    seen = set() if seen is None else seen
    for d in deps.get(layer, ()):
        if d in deps and d not in seen:
            seen.add(d)
            below(d, seen)
    return seen
broken = []
for layer in deps:
    allowed = below(layer) | {layer}
    for f in sorted((root / "src/tightfit" / layer).rglob("*.[ch]pp")):
        for n, line in enumerate(f.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"tightfit/(\w+)/', line)
            if m and m.group(1) not in allowed:
                broken.append(f"{f.relative_to(root)}:{n}: layer '{layer}' includes '{m.group(1)}'")
print("\n".join(broken) if broken else f"layers: {len(deps)} checked, no upward include")
sys.exit(1 if broken else 0)

#!/usr/bin/env bash
# The built-in demo: runs tightfit's main job on a built-in example and prints where
# the results are. Usage: scripts/demo.sh PATH/TO/tightfit OUTDIR
set -euo pipefail
bin=${1:?tightfit binary}
out=${2:?output directory}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
"$bin" version
# A two-panel sleeve on a soft forearm-sized cylinder: the panels are cut from the body
# by planes, flattened, scaled down 10 % around and 5 % along, meshed, sewn, embedded on
# the body's Loop limit surface and brought to equilibrium with the body.
scene="$here/examples/sleeve_two_panels.json"
"$bin" layout "$scene" --out "$out/layout"
"$bin" simulate "$scene" --out "$out/fit"
# Pattern optimization, the quickest of the paper's examples (Fig. 3b: two rectangular
# pieces on a soft cylinder, shape objective towards a tapered cylinder), cut short
# after a few L-BFGS iterations so the demo stays around a minute; the full run is
# `tightfit optimize examples/optimize_cylinder_tapered.json --out DIR` (150 iterations).
"$bin" optimize "$here/examples/optimize_cylinder_tapered.json" --out "$out/optimize" \
  --max-iterations 8
echo
echo "demo results:"
echo "  patterns:  $out/fit/pattern.svg  $out/fit/pattern_a4.pdf  $out/fit/pattern.dxf  $out/fit/pieces.json"
echo "  fit:       $out/fit/garment.ply  $out/fit/body.ply  $out/fit/result.json"
if [ -f "$out/fit/report.html" ]; then echo "  report:    $out/fit/report.html"; fi
echo "  optimized: $out/optimize/pattern.svg  $out/optimize/history.json  $out/optimize/result.json"
if [ -f "$out/optimize/report.html" ]; then echo "  report:    $out/optimize/report.html"; fi

#!/usr/bin/env bash
# The built-in demo: runs tightfit's main job on a built-in example and prints where
# the results are. Usage: scripts/demo.sh PATH/TO/tightfit OUTDIR
set -euo pipefail
bin=${1:?tightfit binary}
out=${2:?output directory}
mkdir -p "$out"
"$bin" version
# A soft cylinder (radius 5 cm, 30 cm long, rounded ends) with a 15 mm pinned core.
"$bin" body --generator cylinder --radius 0.05 --length 0.3 --edge-length 0.01 \
  --soft-tissue 0.015 --out "$out/body"

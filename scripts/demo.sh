#!/usr/bin/env bash
# The built-in demo: runs tightfit's main job on a built-in example and prints where
# the results are. Usage: scripts/demo.sh PATH/TO/tightfit OUTDIR
set -euo pipefail
bin=${1:?tightfit binary}
out=${2:?output directory}
mkdir -p "$out"
"$bin" version

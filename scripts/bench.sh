#!/usr/bin/env bash
# Runs every benchmark of a build folder and keeps the JSON results in out/bench/.
# Usage: scripts/bench.sh BUILD_DIR
set -euo pipefail
build=${1:?build folder}
mkdir -p out/bench
for b in "$build"/bench/*_bench; do
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_out="out/bench/$name.json" --benchmark_out_format=json
done

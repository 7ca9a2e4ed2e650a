#!/usr/bin/env bash
# Fuzzes every reader of tightfit with libFuzzer (`make fuzz`): builds fuzz/*_fuzz.cpp
# with Debian's clang, AddressSanitizer and UBSan into build/fuzz, makes seed corpora
# from the repository's test files plus files a real run writes (VTU, state.json,
# checkpoint.json, pieces.json), and runs each target for FUZZ_SECONDS (default 60)
# seconds. Findings (crash-*, timeout-*, oom-*) land in build/fuzz/findings/TARGET/;
# the script exits 1 when any target found one. Each finding, once fixed, goes into
# tests/fuzz_regressions/READER/ (READER: the target's name without "_fuzz"), where
# `make test` reads it again (tests/app/fuzz_regression_test.cpp).
# Usage: [FUZZ_SECONDS=S] [FUZZ_JOBS=N] scripts/fuzz.sh [TARGET...]   (default: all
# targets, one at a time; FUZZ_JOBS runs N targets at once, each for S seconds of wall
# time, so a slower machine runs fewer inputs: compare the executed-units counts printed).
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${FUZZ_SECONDS:-60}"
BUILD=build/fuzz
RELEASE="${TIGHTFIT_RELEASE_BUILD:-build/release}"

bash scripts/install-deps.sh --fuzz
mkdir -p "$BUILD"
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DTIGHTFIT_BUILD_FUZZERS=ON -DTIGHTFIT_SANITIZE=ON -DTIGHTFIT_BUILD_TESTS=OFF \
  -DTIGHTFIT_BUILD_BENCH=OFF -DTIGHTFIT_PCH=OFF > "$BUILD/configure.log"
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  for f in fuzz/*_fuzz.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
cmake --build "$BUILD" -j "$(nproc)" --target "${targets[@]}"

# Seeds: the repository's files of each format, and the outputs of one small run of the
# release build (made if missing).
seeds="$BUILD/seeds"
if [ ! -d "$seeds/run" ]; then
  [ -x "$RELEASE/tightfit" ] || { echo "fuzz: $RELEASE/tightfit is missing (make build)"; exit 2; }
  mkdir -p "$seeds"
  rm -rf "$seeds/run.tmp" && mkdir -p "$seeds/run.tmp"
  echo '{"generator": "sphere", "radius": 0.05, "edge_length": 0.02}' > "$seeds/run.tmp/body.json"
  "$RELEASE/tightfit" body "$seeds/run.tmp/body.json" --out "$seeds/run.tmp/body" > /dev/null
  "$RELEASE/tightfit" optimize examples/optimize_sleeve_stretch.json --max-iterations 2 \
    --out "$seeds/run.tmp/optimize" > /dev/null
  mv "$seeds/run.tmp" "$seeds/run"
fi
corpus_files() {
  case "$1" in
    obj_fuzz) ls tests/geometry/data/*.obj examples/data/*.obj "$seeds/run/body/surface.obj" ;;
    ply_fuzz) ls tests/geometry/data/*.ply "$seeds/run/optimize/garment.ply" ;;
    off_fuzz) ls tests/geometry/data/*.off ;;
    stl_fuzz) ls tests/geometry/data/*.stl ;;
    vtu_fuzz) ls "$seeds/run/body/volume.vtu" ;;
    scene_fuzz) ls examples/*.json ;;
    json_fuzz) ls examples/*.json "$seeds/run/optimize/checkpoint.json" ;;
    state_fuzz) ls "$seeds/run/optimize/state.json" ;;
    checkpoint_fuzz) ls "$seeds/run/optimize/checkpoint.json" ;;
    pieces_fuzz) ls "$seeds/run/optimize/pieces.json" ;;
    skeleton_fuzz) ls data/rig/mh_child.joints.json ;;
    skin_weights_fuzz) printf '%s\n' '{"name": "w", "weights": {"root": [[0, 0.5], [1, 1.0]], "spine05": [[0, 0.5], [2, 1], [3, 1]]}}' > "$seeds/weights.mhw"; ls "$seeds/weights.mhw" ;;
    layout_fuzz) ls tests/garment/data/*.json ;;
    bvh_fuzz) ls data/rig/*.bvh ;;
    fabric_fuzz) ls data/fabrics/*.json ;;
    strip_csv_fuzz) ls tests/scene/data/strip_tests/*.csv ;;
  esac
}

# One target's run: its corpus, then libFuzzer for SECONDS_PER_TARGET seconds; its log in
# $BUILD/TARGET.log, findings in $BUILD/findings/TARGET/. Exit status 1 on a finding.
fuzz_target() {
  local t="$1" corpus="$BUILD/corpus/$1" findings="$BUILD/findings/$1"
  mkdir -p "$corpus" "$findings"
  for f in $(corpus_files "$t"); do cp "$f" "$corpus/"; done
  if ! TMPDIR="$BUILD/tmp" ASAN_OPTIONS=detect_leaks=0 "$BUILD/fuzz/$t" "$corpus" \
      -max_total_time="$SECONDS_PER_TARGET" -max_len=262144 -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$findings/" > "$BUILD/$t.log" 2>&1; then
    echo "fuzz: $t FOUND A PROBLEM: $(ls "$findings")"
    return 1
  fi
}

# FUZZ_JOBS targets run at once (default 1): each still runs FUZZ_SECONDS of wall time.
JOBS="${FUZZ_JOBS:-1}"
mkdir -p "$BUILD/tmp"
status=0
pids=()
names=()
report() {  # waits for the oldest running target and prints its line
  local pid="${pids[0]}" t="${names[0]}"
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
  wait "$pid" || status=1
  echo "fuzz: $t: $(grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$BUILD/$t.log" | tr '\n' ' ')"
}
for t in "${targets[@]}"; do
  [ "${#pids[@]}" -ge "$JOBS" ] && report
  echo "fuzz: $t for ${SECONDS_PER_TARGET} s"
  fuzz_target "$t" &
  pids+=("$!")
  names+=("$t")
done
while [ "${#pids[@]}" -gt 0 ]; do report; done
exit $status

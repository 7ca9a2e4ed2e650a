#!/usr/bin/env bash
# Installs every Debian (bookworm) package tightfit needs to build, test and export.
# Idempotent; run as root (or with sudo available). Nothing is downloaded at build time.
set -euo pipefail

BUILD_PKGS=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libosd-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libtet1.5-dev nlohmann-json3-dev libcli11-dev
  libopenblas0-pthread
  libnanoflann-dev libcairo2-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)
# Clients used by the tests to check exports with real third-party readers, and valgrind
# (memcheck of the reader and physics tests, scripts/memcheck.sh), and GNU parallel
# (`tightfit grade` through a batch engine, tests/app/grade_cli_test.cpp), clang-format and
# clang-tidy (make format-check, make check-naming: CONTRIBUTING.md).
CHECK_PKGS=(
  python3 python3-ezdxf python3-meshio python3-numpy python3-jsonschema librsvg2-bin poppler-utils librecad
  chromium
  valgrind
  parallel
  clang-format clang-tidy
)
# Node runs the report's npm packages (three.js, gltf-validator, playwright-core); a
# machine that already has npm (e.g. a newer Node) keeps it. playwright-core is pinned
# to 1.60, the last release that supports bookworm's Node 18 (1.62+ need Node 20).
if ! command -v npm >/dev/null 2>&1; then CHECK_PKGS+=(nodejs npm); fi
# `--fuzz` (scripts/fuzz.sh): clang with libFuzzer and the sanitizer runtimes.
if [ "${1:-}" = "--fuzz" ]; then CHECK_PKGS+=(clang libclang-rt-dev); fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${BUILD_PKGS[@]}" "${CHECK_PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#BUILD_PKGS[@]}+${#CHECK_PKGS[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# CHOLMOD calls the BLAS/LAPACK behind Debian's libblas.so.3 / liblapack.so.3
# alternatives. Point them at OpenBLAS (pthread build): its supernodal kernels are about
# 4x faster than the reference BLAS and use every core. `tightfit simulate` records the
# BLAS it ran on in result.json ("compute").
arch="$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)"
for lib in libblas.so.3 liblapack.so.3; do
  target="/usr/lib/$arch/openblas-pthread/$lib"
  if [ -e "$target" ] && [ "$(readlink -f "/usr/lib/$arch/$lib")" != "$(readlink -f "$target")" ]; then
    echo "install-deps: $lib -> OpenBLAS"
    $SUDO update-alternatives --set "$lib-$arch" "$target"
  fi
done

# The report's npm packages, exactly as locked in report/package-lock.json. Skipped
# when node_modules was installed from the same lock file. No browser is downloaded:
# the tests drive Debian's /usr/bin/chromium.
report_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/report"
lock_sum="$(sha256sum "$report_dir/package-lock.json" | cut -d' ' -f1)"
stamp="$report_dir/node_modules/.tightfit-lock-sha256"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$lock_sum" ]; then
  echo "install-deps: report/node_modules up to date"
else
  echo "install-deps: npm ci --prefix report"
  PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --prefix "$report_dir" --no-audit --no-fund
  echo "$lock_sum" > "$stamp"
fi

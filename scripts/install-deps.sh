#!/usr/bin/env bash
# Installs every Debian (bookworm) package tightfit needs to build, test and export.
# Idempotent; run as root (or with sudo available). Nothing is downloaded at build time.
set -euo pipefail

BUILD_PKGS=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libosd-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libtet1.5-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  liblbfgspp-dev libnanoflann-dev libcairo2-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)
# Clients used by the tests to check exports with real third-party readers.
CHECK_PKGS=(
  python3 python3-ezdxf python3-meshio python3-numpy python3-jsonschema librsvg2-bin poppler-utils librecad
)

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
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"

#!/usr/bin/env bash
# Installs eqmesh's build and test dependencies on Debian bookworm (run as root,
# or with sudo available). Idempotent: packages already present are skipped and
# apt-get update runs only when something is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libtinygltf-dev libdraco-dev draco libeigen3-dev libjpeg-dev libpng-dev
  libgtest-dev googletest libcli11-dev nlohmann-json3-dev zlib1g-dev libstb-dev
  gltfpack gzip python3 time
  clang libclang-rt-14-dev
)
# EQMESH_SETUP_TESTS=1 (scripts/test.sh sets it): gnuplot, which the benchmark
# smoke test needs for its R-D plots; the demo does without.
if [[ "${EQMESH_SETUP_TESTS:-0}" == "1" ]]; then
  PACKAGES+=(gnuplot-nox)
fi
# EQMESH_SETUP_EXTRAS=1: the Khronos glTF-Validator (npm) that the glTF tests run
# when present, and gnuplot for the benchmark's R-D plots (bench/run_bench.py).
if [[ "${EQMESH_SETUP_EXTRAS:-0}" == "1" ]]; then
  PACKAGES+=(nodejs npm gnuplot-nox)
fi
# EQMESH_SETUP_WEB=1 (or the extras): the WebAssembly decoder's build and its test
# in headless Chromium (scripts/test-web.sh). A flag of its own: the extras' Debian
# npm cannot join a node from elsewhere (nodesource), while these packages can.
if [[ "${EQMESH_SETUP_EXTRAS:-0}" == "1" || "${EQMESH_SETUP_WEB:-0}" == "1" ]]; then
  PACKAGES+=(emscripten chromium chromium-driver)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup-debian: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "setup-debian: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"

#!/usr/bin/env bash
# Installs eqmesh's build and test dependencies on Debian bookworm (run as root,
# or with sudo available). Idempotent: packages already present are skipped and
# apt-get update runs only when something is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libtinygltf-dev libdraco-dev draco libeigen3-dev
  libgtest-dev googletest libcli11-dev nlohmann-json3-dev zlib1g-dev libstb-dev
  gltfpack gzip python3 time gnuplot-nox
  clang libclang-rt-14-dev
)
# Optional extras for the validator and the benchmark plots (issue 5/6 tooling).
if [[ "${EQMESH_SETUP_EXTRAS:-0}" == "1" ]]; then
  PACKAGES+=(nodejs npm gnuplot-nox)
fi
# The web loader's wasm build and real-browser test (issue 8, scripts/test-web.sh).
# A flag of its own: the extras' Debian npm cannot join a node from elsewhere
# (nodesource), while these packages can.
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

#!/usr/bin/env bash
# Configures and builds eqmesh into BUILD_DIR (default build/). Extra arguments
# go to cmake's configure step, e.g. scripts/build.sh -DEQMESH_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
JOBS="${JOBS:-$(nproc)}"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS"

#!/usr/bin/env bash
# Builds the WebAssembly decoder (web/CMakeLists.txt) with Debian's emscripten into
# WASM_BUILD_DIR (default build-wasm/, where samples/web/ looks): eqmesh_decoder.mjs (ES module factory) and
# eqmesh_decoder.wasm. Nothing is downloaded: Debian's emscripten ships its
# system libraries prebuilt, and the Draco decoder the module calls comes from
# three.js's npm package at run time (web/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${WASM_BUILD_DIR:-build-wasm}"
JOBS="${JOBS:-2}"
if ! command -v emcmake >/dev/null 2>&1; then
  echo "build-wasm: emcmake not found (apt-get install emscripten)" >&2
  exit 1
fi
# Debian's emscripten finds its node modules (acorn) through Debian's node path;
# a node from elsewhere (nodesource) does not search it by default.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
# Debian's cache under /usr/share/emscripten is prebuilt and frozen; a private copy
# is needed only if a flag ever asks for a library variant it lacks.
emcmake cmake -S web -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS"
wasm="$BUILD_DIR/eqmesh_decoder.wasm"
echo "build-wasm: $wasm $(stat -c %s "$wasm") bytes, $(gzip -9c "$wasm" | wc -c) gzipped"

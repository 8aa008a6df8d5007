#!/usr/bin/env bash
# The installed package as an engine sees it: `cmake --install` of BUILD_DIR into a
# scratch prefix, samples/consumer (a C program) configured with find_package(eqmesh)
# and built against it, then run on a stream the native tool encodes; its decodes
# must reach the stream's finest level and keep a triangle budget; its C++ program
# encodes with eqmesh::encoder and loads a compressed glTF with eqmesh::loader. Then
# the same with the decoder built alone (no encoder, tools or Draco: a compiler, CMake
# and Eigen), consumed as if Eigen were absent, which must refuse a Draco-coded stream
# with a clear error.
#   BUILD_DIR  a configured and built tree (default build-test)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build-test}"
PREFIX="$BUILD_DIR/install-test"
CONSUMER="$BUILD_DIR/consumer"
rm -rf "$PREFIX" "$CONSUMER"
cmake --install "$BUILD_DIR" --prefix "$PREFIX" >/dev/null
cmake -S samples/consumer -B "$CONSUMER" -G Ninja -DCMAKE_PREFIX_PATH="$(realpath "$PREFIX")" >/dev/null
cmake --build "$CONSUMER" >/dev/null
"$BUILD_DIR/tools/eqmesh" encode samples/meshes/blob.obj "$CONSUMER/blob.eqm" --bpv 2 --levels 4 >/dev/null
out="$("$CONSUMER/decode_stream" "$CONSUMER/blob.eqm" 2000)"
echo "$out"
grep -q "level 4 of 4" <<<"$out" || { echo "test-install: the finest level never arrived" >&2; exit 1; }
grep -q "one call: level [0-9]*, [0-9]* vertices, \([0-9]\|[0-9][0-9]\|[0-9][0-9][0-9]\|1[0-9][0-9][0-9]\|2000\) triangles" <<<"$out" ||
  { echo "test-install: the 2000-triangle budget was not kept" >&2; exit 1; }
# The C++ targets: encode with eqmesh::encoder, load a compressed glTF with eqmesh::loader.
"$BUILD_DIR/tools/eqmesh" encode samples/meshes/blob.obj "$CONSUMER/blob.glb" --bpv 2 --levels 4 >/dev/null
out="$("$CONSUMER/encode_and_load" samples/meshes/blob.obj "$CONSUMER/blob.glb")"
echo "$out"
grep -q "^encoded 10242 vertices into [0-9]* bytes; decoded [0-9]* vertices" <<<"$out" &&
  grep -q "^loaded .*blob.glb: [1-9][0-9]* vertices" <<<"$out" ||
  { echo "test-install: the C++ consumer did not encode and load" >&2; exit 1; }

# The decoder alone.
ALONE="$BUILD_DIR/decoder-only"
cmake -S . -B "$ALONE" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DEQMESH_BUILD_ENCODER=OFF -DEQMESH_BUILD_TOOLS=OFF -DEQMESH_BUILD_TESTS=OFF \
  -DEQMESH_WITH_DRACO=OFF >/dev/null
cmake --build "$ALONE" -j "${JOBS:-2}" >/dev/null
rm -rf "$ALONE/install" "$ALONE/consumer"
cmake --install "$ALONE" --prefix "$ALONE/install" >/dev/null
# As an engine without Eigen sees it: the C API needs only the C++ runtime.
cmake -S samples/consumer -B "$ALONE/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$(realpath "$ALONE/install")" \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=TRUE >/dev/null
cmake --build "$ALONE/consumer" >/dev/null
"$ALONE/consumer/decode_stream" "$CONSUMER/blob.eqm" | grep -q "level 4 of 4" ||
  { echo "test-install: the decoder built alone did not decode the stream" >&2; exit 1; }
# A small second part travels in the kept-exactly chunk, compact: no Draco needed.
{ cat samples/meshes/blob.obj
  n="$(grep -c '^v ' samples/meshes/blob.obj)"
  printf 'v 2 0 0\nv 2.1 0 0\nv 2 0.1 0\nv 2 0 0.1\n'
  for f in "1 3 2" "1 2 4" "1 4 3" "2 3 4"; do
    set -- $f
    echo "f $(($1 + n)) $(($2 + n)) $(($3 + n))"
  done; } >"$CONSUMER/two_parts.obj"
"$BUILD_DIR/tools/eqmesh" encode "$CONSUMER/two_parts.obj" "$CONSUMER/two_parts.eqm" --bpv 2 --levels 4 >/dev/null
"$BUILD_DIR/tools/eqmesh" info "$CONSUMER/two_parts.eqm" | grep -q "compact kept-exactly chunk" ||
  { echo "test-install: the kept part did not travel in a compact chunk" >&2; exit 1; }
"$ALONE/consumer/decode_stream" "$CONSUMER/two_parts.eqm" | grep -q "level 4 of 4" ||
  { echo "test-install: the decoder built alone did not decode a stream with a kept part" >&2; exit 1; }
"$BUILD_DIR/tools/eqmesh" encode samples/meshes/blob.obj "$CONSUMER/blob_draco.eqm" --bpv 2 --levels 2 --draco-base >/dev/null 2>&1
if err="$("$ALONE/consumer/decode_stream" "$CONSUMER/blob_draco.eqm" 2>&1)"; then
  echo "test-install: a Draco-coded stream decoded without Draco" >&2
  exit 1
fi
grep -q "built without Draco" <<<"$err" || { echo "test-install: unclear error: $err" >&2; exit 1; }
echo "test-install: passed"

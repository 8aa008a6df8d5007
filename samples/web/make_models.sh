#!/usr/bin/env bash
# Makes the demo's models (samples/web/models/, gitignored) with the native eqmesh
# tool: each mesh encoded as .glb, plus a .gltf + .bin split of it for streaming
# with HTTP Range requests. Meshes are read in place, never copied into the repo.
#   samples/web/make_models.sh [MESH ...]    default: ../shared/meshes/bench/stanford-bunny.obj and
#                                             the textured ../shared/meshes/textured/duck.glb
# EQMESH=path/to/eqmesh picks the tool (default: build-web-native, built if missing);
# BPV sets the rate (default 2); OUT_DIR the folder.
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT_DIR="${OUT_DIR:-samples/web/models}"
BPV="${BPV:-2}"
EQMESH="${EQMESH:-build-web-native/tools/eqmesh}"
if [[ ! -x "$EQMESH" ]]; then
  BUILD_DIR=build-web-native JOBS="${JOBS:-2}" bash scripts/build.sh -DEQMESH_BUILD_TESTS=OFF
fi
meshes=("$@")
((${#meshes[@]})) || meshes=(../shared/meshes/bench/stanford-bunny.obj ../shared/meshes/textured/duck.glb)
mkdir -p "$OUT_DIR"
for mesh in "${meshes[@]}"; do
  name="$(basename "$mesh")"
  name="${name%%.*}"
  "$EQMESH" encode "$mesh" "$OUT_DIR/$name.glb" --bpv "$BPV"
  python3 samples/web/split_glb.py "$OUT_DIR/$name.glb" "$OUT_DIR/split"
  echo "make_models: $OUT_DIR/$name.glb ($(stat -c %s "$OUT_DIR/$name.glb") bytes), $OUT_DIR/split/$name.gltf"
done

#!/usr/bin/env bash
# The main job on the bundled sample: installs what is missing, builds (Release),
# then diagnoses samples/meshes/blob.obj, makes a noisy copy and measures its error.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
BUILD_DIR="${BUILD_DIR:-build}" bash scripts/build.sh -DEQMESH_BUILD_TESTS=OFF
EQ="${BUILD_DIR:-build}/tools/eqmesh"
OUT="${BUILD_DIR:-build}/demo"
mkdir -p "$OUT"
SAMPLE=samples/meshes/blob.obj
echo "== eqmesh info $SAMPLE"
"$EQ" info "$SAMPLE"
echo "== eqmesh perturb (0.1 % of the diagonal) and compare"
"$EQ" perturb "$SAMPLE" "$OUT/blob_noisy.ply" --noise 0.001
"$EQ" compare "$SAMPLE" "$OUT/blob_noisy.ply"

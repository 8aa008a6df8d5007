#!/usr/bin/env bash
# The main job on the bundled sample: installs what is missing, builds (Release),
# diagnoses samples/meshes/blob.obj, then remeshes + encodes it at 2 bits per input
# vertex, decodes the stream and measures the decoded mesh against the original.
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
echo "== eqmesh encode (remesh + EQ coder, 2 bits per input vertex)"
"$EQ" encode "$SAMPLE" "$OUT/blob.eqm" --bpv 2
echo "== eqmesh decode"
"$EQ" decode "$OUT/blob.eqm" "$OUT/blob_decoded.ply"
echo "== eqmesh compare (original vs decoded)"
"$EQ" compare "$SAMPLE" "$OUT/blob_decoded.ply"
echo "== done: the command is $EQ (every subcommand has --help); outputs are in $OUT/"

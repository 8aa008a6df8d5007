#!/usr/bin/env bash
# Decode time of the WebAssembly decoder in headless Chromium against the native
# C++ decoder, on encoded .glb files (default: every .glb in build-web-native/bench/,
# e.g. the bench meshes encoded with `eqmesh encode MESH OUT.glb --bpv 1`). Both
# sides decode the whole stream and compute unit normals, RUNS times after a
# warm-up; the table shows medians. Needs scripts/build-wasm.sh and
# build-web-native (BUILD_DIR=build-web-native bash scripts/build.sh) first.
#   web/bench/run_bench.sh [GLB ...]
set -euo pipefail
cd "$(dirname "$0")/../.."
NATIVE="${NATIVE_BUILD:-build-web-native}"
RUNS="${RUNS:-10}"
WORK="$NATIVE/bench/streams"
LOOP="$NATIVE/native_decode_loop"
mkdir -p "$WORK"
glbs=("$@")
((${#glbs[@]})) || glbs=("$NATIVE"/bench/*.glb)

if [[ ! "$LOOP" -nt web/bench/native_decode_loop.cpp || ! "$LOOP" -nt "$NATIVE/lib/coding/libeqmesh_decoder.a" ]]; then
  L="$NATIVE/lib"
  g++ -O3 -DNDEBUG -std=c++17 -Ilib -isystem /usr/include/eigen3 web/bench/native_decode_loop.cpp \
    -Wl,--start-group "$L"/coding/libeqmesh_{decoder,eq_decoder,entropy,quantizer_model}.a \
    "$L/coding/zerotree/libeqmesh_zerotree.a" "$L/wavelet/libeqmesh_wavelet.a" "$L/mesh/libeqmesh_mesh.a" \
    -Wl,--end-group -ldraco -o "$LOOP"
fi

streams=()
for glb in "${glbs[@]}"; do
  name="$(basename "$glb" .glb)"
  python3 samples/web/split_glb.py --stream "$glb" "$WORK/$name.eqm"
  streams+=("$WORK/$name.eqm")
done
# glibc hands large freed blocks back to the kernel, so each native decode
# page-faults its memory afresh, which a wasm heap never does; the "warm heap" run
# keeps them, for a like-for-like comparison.
WARM_HEAP="glibc.malloc.mmap_threshold=4294967295:glibc.malloc.trim_threshold=4294967295"
for s in "${streams[@]}"; do
  echo "{\"stream\": \"$(basename "$s")\", \"bytes\": $(stat -c %s "$s"), \"native\": $("$LOOP" "$s" "$RUNS"),\
 \"native_warm\": $(GLIBC_TUNABLES="$WARM_HEAP" "$LOOP" "$s" "$RUNS")}"
done > "$WORK/native.jsonl"
node tests/web/bench_decode.mjs "$RUNS" "${streams[@]}" > "$WORK/browser.jsonl"
python3 - "$WORK" <<'PY'
import json, sys
work = sys.argv[1]
native = {r["stream"]: r for r in map(json.loads, open(f"{work}/native.jsonl"))}
print(f"{'stream':<20}{'bytes':>7}{'vertices':>10}{'native':>9}{'warm heap':>11}{'wasm':>8}{'wasm 1st':>10}  (median ms)")
for b in map(json.loads, open(f"{work}/browser.jsonl")):
    n = native[b["stream"]]
    assert n["native"]["vertices"] == b["vertices"], b["stream"]
    print(f"{b['stream']:<20}{n['bytes']:>7}{b['vertices']:>10}{n['native']['median_ms']:>9.1f}"
          f"{n['native_warm']['median_ms']:>11.1f}{b['median_ms']:>8.1f}{b['first_ms']:>10.1f}")
PY

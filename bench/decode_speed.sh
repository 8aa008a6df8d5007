#!/usr/bin/env bash
# Single-threaded decode speed against Draco, as issue #31 checks it: each mesh is
# encoded once with `eqmesh encode --bpv B` and once with `draco_encoder -qp 11 -cl 10`;
# then, alternating, RUNS decodes of each: `EQMESH_THREADS=1 eqmesh decode --json`
# (its decode_seconds) and `draco_decoder` (the milliseconds it prints). Both
# figures leave out reading and writing files. Prints one Markdown row per mesh
# and rate: output triangles, median seconds, output triangles per second, and
# eqmesh's rate over Draco's.
#
# usage: bench/decode_speed.sh [MESH ...]   (default: horse, stanford-bunny, armadillo_50k)
# env:   EQMESH (default build/tools/eqmesh), RATES ("1 4"), RUNS (5)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
eqmesh="${EQMESH:-$root/build/tools/eqmesh}"
meshes_dir="$root/../shared/meshes/bench"
rates="${RATES:-1 4}"
runs="${RUNS:-5}"
meshes=("$@")
((${#meshes[@]})) || meshes=("$meshes_dir/horse.ply" "$meshes_dir/stanford-bunny.obj" "$meshes_dir/armadillo_50k.obj")

[[ -x "$eqmesh" ]] || { echo "decode_speed.sh: no eqmesh binary at $eqmesh (set EQMESH)" >&2; exit 1; }
command -v draco_decoder >/dev/null || { echo "decode_speed.sh: needs draco_encoder/draco_decoder (Debian: draco)" >&2; exit 1; }

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

echo "| mesh | codec | setting | bytes | triangles out | median decode s | triangles/s | eqmesh / Draco |"
echo "|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name="$(basename "${mesh%.*}")"
  draco_encoder -i "$mesh" -o "$tmp/$name.drc" -qp 11 -cl 10 --skip NORMAL --skip TEX_COORD >/dev/null
  draco_triangles="$(draco_decoder -i "$tmp/$name.drc" -o "$tmp/$name.draco.ply" >/dev/null &&
    "$eqmesh" info "$tmp/$name.draco.ply" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["faces"])')"
  for bpv in $rates; do
    echo "decode_speed.sh: $name at $bpv bpv" >&2
    "$eqmesh" encode "$mesh" "$tmp/$name.eqm" --bpv "$bpv" >/dev/null
    : >"$tmp/eq.s"
    : >"$tmp/draco.s"
    eq_triangles=0
    for ((i = 0; i < runs; ++i)); do
      EQMESH_THREADS=1 "$eqmesh" decode "$tmp/$name.eqm" "$tmp/$name.ply" --json >"$tmp/eq.json"
      python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["decode_seconds"])' "$tmp/eq.json" >>"$tmp/eq.s"
      eq_triangles="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["faces"])' "$tmp/eq.json")"
      draco_decoder -i "$tmp/$name.drc" -o "$tmp/$name.draco.ply" |
        sed -n 's/.*(\([0-9.]*\) ms to decode).*/\1/p' | awk '{ print $1 / 1000 }' >>"$tmp/draco.s"
    done
    eq_s="$(median <"$tmp/eq.s")"
    draco_s="$(median <"$tmp/draco.s")"
    python3 - "$name" "$bpv" "$(stat -c %s "$tmp/$name.eqm")" "$eq_triangles" "$eq_s" \
      "$(stat -c %s "$tmp/$name.drc")" "$draco_triangles" "$draco_s" <<'PY'
import sys
name, bpv, eq_bytes, eq_tri, eq_s, dr_bytes, dr_tri, dr_s = sys.argv[1:]
eq_rate = int(eq_tri) / float(eq_s)
dr_rate = int(dr_tri) / float(dr_s) if float(dr_s) > 0 else float("inf")
print(f"| {name} | eqmesh | {bpv} bpv | {int(eq_bytes):,} | {int(eq_tri):,} | {float(eq_s):.3f} | {eq_rate / 1e6:.2f} M | {eq_rate / dr_rate:.2f} |")
print(f"| {name} | draco | qp 11, cl 10 | {int(dr_bytes):,} | {int(dr_tri):,} | {float(dr_s):.3f} | {dr_rate / 1e6:.2f} M | |")
PY
  done
done

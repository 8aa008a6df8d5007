#!/usr/bin/env bash
# Rate-distortion sweep of the eqmesh codec on the bench meshes.
#
# For each mesh, transform (unlifted, lifted) and target rate (bits per input
# vertex): `eqmesh encode --bpv B --measure --json` (remesh + encode + decode +
# Metro-style PSNR against the input) and a timed `eqmesh decode`; then, for the
# 1 bpv stream, `eqmesh decode --level K` for every level with its vertex count,
# the stream prefix it needs and (when the `compare` command is built) its PSNR.
#
# usage: bench/codec_rd.sh [BUILD_DIR] [OUT_DIR] [MESH...]
#   defaults: build, bench/out/codec_rd, horse and stanford-bunny.
# Env: RATES="0.25 0.5 1 2 3 4", TRANSFORMS="unlifted lifted".
# Output: OUT_DIR/results.jsonl (one JSON object per encode), OUT_DIR/levels.jsonl.
set -euo pipefail

here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/bench/out/codec_rd}"
shift $(( $# > 2 ? 2 : $# )) || true
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  meshes=("$here/../shared/meshes/bench/horse.ply" "$here/../shared/meshes/bench/stanford-bunny.obj")
fi
rates="${RATES:-0.25 0.5 1 2 3 4}"
transforms="${TRANSFORMS:-unlifted lifted}"
eqmesh="$build/tools/eqmesh"
mkdir -p "$out"
: > "$out/results.jsonl"
: > "$out/levels.jsonl"

for mesh in "${meshes[@]}"; do
  name="$(basename "$mesh")"; name="${name%%.*}"
  for transform in $transforms; do
    for bpv in $rates; do
      stream="$out/${name}_${transform}_${bpv}.eqm"
      json="$("$eqmesh" encode "$mesh" "$stream" --bpv "$bpv" --transform "$transform" --measure --json)"
      dec_start=$(date +%s.%N)
      "$eqmesh" decode "$stream" "$out/${name}_${transform}_${bpv}.ply" > /dev/null
      dec_end=$(date +%s.%N)
      echo "$json" | python3 -c "import json,sys; d=json.load(sys.stdin); d['mesh']='$name'; d['target_bpv']=$bpv; d['decode_seconds']=$dec_end-$dec_start; print(json.dumps(d))" >> "$out/results.jsonl"
      tail -n 1 "$out/results.jsonl" | python3 -c "import json,sys; d=json.load(sys.stdin); print('%-16s %-9s %5s bpv -> %.3f bpv %8d B %6.2f dB  enc %.1fs (remesh %.1fs) dec %.2fs' % (d['mesh'], d['transform'], d['target_bpv'], d['bpv'], d['bytes'], d.get('psnr_db', float('nan')), d['encode_seconds'], d['remesh_seconds'], d['decode_seconds']))"
    done
    # Progressive access: every level of the 1 bpv stream.
    stream="$out/${name}_${transform}_1.eqm"
    if [ -f "$stream" ] && "$eqmesh" --help | grep -q "^  compare"; then
      levels="$(python3 -c "import json; print([json.loads(l) for l in open('$out/results.jsonl') if '\"${name}\"' in l][-1]['levels'])")"
      for k in $(seq 0 "$levels"); do
        "$eqmesh" decode "$stream" "$out/${name}_${transform}_L$k.ply" --level "$k" --json > "$out/dec.json"
        "$eqmesh" compare "$mesh" "$out/${name}_${transform}_L$k.ply" --json > "$out/cmp.json" || true
        python3 - "$out" "$name" "$transform" "$k" <<'PY' >> "$out/levels.jsonl"
import json, sys
out, name, transform, k = sys.argv[1:]
d = json.load(open(out + "/dec.json"))
try:
    c = json.load(open(out + "/cmp.json"))
except Exception:
    c = {}
print(json.dumps({"mesh": name, "transform": transform, "level": int(k),
                  "vertices": d["vertices"], "prefix_bytes": (d["level_offsets"] + [d["bytes"]])[int(k)] if int(k) < len(d["level_offsets"]) else d["bytes"],
                  "psnr_db": c.get("psnr_db")}))
PY
        tail -n 1 "$out/levels.jsonl"
      done
    fi
  done
done

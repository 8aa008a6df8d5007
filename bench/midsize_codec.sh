#!/usr/bin/env bash
# Codec bench on typical asset sizes: for every mesh of midsize/ and small/
# (cow.ply aside), `eqmesh encode MESH OUT.eqm --psnr D` as a user runs it, the
# decoded stream measured by `eqmesh compare`, and Draco's bytes at the same
# PSNR (draco_encoder -cl 10, qp 7..14, interpolated linearly in PSNR between the
# two qps around it), on the same canonical float32 copy of the mesh.
#
# usage: bench/midsize_codec.sh [EQMESH_BINARY] [SHARED_MESHES_DIR] [OUT_DIR]
# EQMESH_PSNR=D (default 70); EQMESH_MESHES="knot.off.gz dino.off.gz" picks meshes.
# Prints one row per mesh: eqmesh bytes, bpv, decoded PSNR, levels, base bytes,
# Draco's interpolated bytes and the ratio Draco / eqmesh, then flipped faces
# against the input (`compare --folds`) of the stream decoded whole, of it
# decoded within the input's triangle count (a .glb's default) and of Draco's
# decode at the first qp that reaches the stream's PSNR; the median ratio last.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
eqmesh="${1:-$here/../build/tools/eqmesh}"
meshes="${2:-$here/../../shared/meshes}"
out_dir="${3:-${TMPDIR:-/tmp}/eqmesh_midsize_codec}"
target="${EQMESH_PSNR:-70}"
mkdir -p "$out_dir"
all=(midsize/knot.off.gz midsize/bones.off.gz midsize/mushroom.off.gz midsize/triceratops.off.gz
     midsize/cow.off.gz midsize/dino.off.gz midsize/femur.off.gz midsize/bull.off.gz
     midsize/lion-head.off.gz midsize/mannequin-devil.off.gz midsize/man.off.gz midsize/bear.off.gz
     midsize/diplodocus.off.gz small/bunny_npm.obj small/fandisk.obj small/skull_low_resolution.obj
     small/rocker-arm.off small/max-planck_10k.obj)
# "PSNR flipped-faces faces-of-$1" of $2 against $1.
psnr_folds_of() {
  "$eqmesh" compare "$1" "$2" --folds --json |
    python3 -c 'import json,sys; d = json.load(sys.stdin); print(d["psnr_db"], d["flipped_faces"], d["faces_original"])'
}
printf '%-26s %7s %7s %7s %4s %6s %7s %7s %6s %6s %6s %s\n' mesh bytes bpv psnr lvl base draco ratio folds f_budg \
  f_drc seconds
ratios="$out_dir/ratios.txt"
: > "$ratios"
for rel in "${all[@]}"; do
  name=$(basename "$rel")
  if [ -n "${EQMESH_MESHES:-}" ] && [[ " $EQMESH_MESHES " != *" $name "* ]]; then continue; fi
  [ -f "$meshes/$rel" ] || { echo "$name: missing, skipped"; continue; }
  stem="${name%%.*}"
  canon="$out_dir/$stem.ply"
  "$eqmesh" convert "$meshes/$rel" "$canon" >/dev/null
  start=$(date +%s.%N)
  if ! json=$("$eqmesh" encode "$canon" "$out_dir/$stem.eqm" --psnr "$target" --json 2>"$out_dir/$stem.err"); then
    echo "$name: FAILED: $(tail -1 "$out_dir/$stem.err")"
    continue
  fi
  seconds=$(python3 -c "import time; print('%.1f' % ($(date +%s.%N) - $start))")
  "$eqmesh" decode "$out_dir/$stem.eqm" "$out_dir/$stem.decoded.ply" >/dev/null
  read -r psnr folds input_faces < <(psnr_folds_of "$canon" "$out_dir/$stem.decoded.ply")
  "$eqmesh" decode "$out_dir/$stem.eqm" "$out_dir/$stem.budget.ply" --max-triangles "$input_faces" >/dev/null
  read -r _ budget_folds _ < <(psnr_folds_of "$canon" "$out_dir/$stem.budget.ply")
  rows="$out_dir/$stem.draco"
  : > "$rows"
  for qp in 7 8 9 10 11 12 13 14; do
    draco_encoder -i "$canon" -o "$out_dir/$stem.drc" -qp "$qp" -cl 10 >/dev/null 2>&1
    draco_decoder -i "$out_dir/$stem.drc" -o "$out_dir/$stem.draco.ply" >/dev/null 2>&1
    echo "$qp $(stat -c %s "$out_dir/$stem.drc") $(psnr_folds_of "$canon" "$out_dir/$stem.draco.ply")" >> "$rows"
  done
  python3 - "$name" "$json" "$psnr" "$rows" "$seconds" "$ratios" "$folds" "$budget_folds" <<'PY'
import json, sys
name, d, psnr, rows, seconds, ratios = sys.argv[1], json.loads(sys.argv[2]), float(sys.argv[3]), sys.argv[4], sys.argv[5], sys.argv[6]
folds, budget_folds = sys.argv[7], sys.argv[8]
pts = [tuple(map(float, l.split()[:3])) for l in open(rows)]
draco_folds = next((l.split()[3] for l in open(rows) if float(l.split()[2]) >= psnr), "n/a")
draco = None
for (q0, b0, p0), (q1, b1, p1) in zip(pts, pts[1:]):
    if p0 <= psnr <= p1:
        draco = b0 + (b1 - b0) * (psnr - p0) / (p1 - p0)
ratio = draco / d["bytes"] if draco else float("nan")
if draco:
    open(ratios, "a").write("%f\n" % ratio)
print("%-26s %7d %7.3f %7.2f %4d %6d %7s %7.2f %6s %6s %6s %s" % (name, d["bytes"], d["bpv"], psnr, d["levels"],
      d["base_bytes"], "%.0f" % draco if draco else "n/a", ratio, folds, budget_folds, draco_folds, seconds))
PY
done
python3 - "$ratios" <<'PY'
import statistics, sys
r = [float(l) for l in open(sys.argv[1]) if l.strip()]
if r:
    print("median ratio Draco / eqmesh over %d meshes: %.2f (min %.2f, max %.2f)" % (len(r), statistics.median(r), min(r), max(r)))
PY

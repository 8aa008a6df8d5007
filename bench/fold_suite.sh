#!/usr/bin/env bash
# Fold suite: folded + degenerate faces of the remesh over more samples than the
# five defaults. Fold counts move chaotically with any change to the refinement
# (the untangler clears a crease's fold cluster or leaves all of it), so a change
# is judged on the bench meshes at three base sizes (the default 0.3 %, 0.25 % and
# 0.2 % of the input vertices) and the small meshes at their defaults.
#
# usage: bench/fold_suite.sh [EQMESH_BINARY] [SHARED_MESHES_DIR] > suite.txt
# Prints one row per run (mesh, base-size option, folds, PSNR dB, normal share,
# slivers, seconds) and the totals of the bench runs and of the small-mesh runs.
# About 7 minutes on the 2-core VM.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
eqmesh="${1:-$here/../build/tools/eqmesh}"
meshes="${2:-$here/../../shared/meshes}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# run GROUP MESH [ARGS...]: one remesh, one row; prints input_vertices to fd 3.
run() {
  local group=$1 mesh=$2
  shift 2
  local json
  if ! json=$("$eqmesh" remesh "$mesh" "$tmp/out.srm" --json "$@" 2>"$tmp/err"); then
    echo "$group $(basename "$mesh") $*: FAILED: $(tail -1 "$tmp/err")"
    return
  fi
  python3 - "$json" "$group" "$(basename "$mesh")" "$*" <<'PY'
import json, sys
d = json.loads(sys.argv[1])
print("%-6s %-26s %-20s %6d %7.2f %7.4f %7d %6.2f" % (
    sys.argv[2], sys.argv[3], sys.argv[4].replace(" ", "=") or "default", d["flipped_faces"] + d["degenerate_faces"],
    d["psnr_db"], d["normal_fraction"], d.get("sliver_faces", -1), d["seconds"]))
PY
}

suite() {
for m in stanford-bunny.obj horse.ply armadillo_50k.obj skull_50k.obj igea.ply; do
  in="$meshes/bench/$m"
  [ -f "$in" ] || { echo "bench $m: missing, skipped"; continue; }
  n=$("$eqmesh" info "$in" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["vertices"])')
  run bench "$in"
  run bench "$in" --base-vertices $((n * 25 / 10000))
  run bench "$in" --base-vertices $((n * 20 / 10000))
done
for m in bunny_npm.obj fandisk.obj max-planck_10k.obj rocker-arm.off skull_low_resolution.obj; do
  in="$meshes/small/$m"
  [ -f "$in" ] || { echo "small $m: missing, skipped"; continue; }
  run small "$in"
done
}

printf '%-6s %-26s %-20s %6s %7s %7s %7s %6s\n' group mesh base folds psnr normal slivers s
suite | tee "$tmp/rows"
awk '$1 == "bench" && $4 ~ /^[0-9]+$/ {b += $4} $1 == "small" && $4 ~ /^[0-9]+$/ {s += $4}
     END {printf "folds: bench %d, small %d\n", b, s}' "$tmp/rows"

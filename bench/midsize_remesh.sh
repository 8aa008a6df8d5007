#!/usr/bin/env bash
# Remesh bench on typical asset sizes: `eqmesh remesh --json` on every mesh of
# midsize/ and small/ (cow.ply aside: it is a non-manifold edge case), one row each.
# Bars (bench/README_remesh.md): PSNR >= 80 dB against the input, 0 flipped faces
# (x_flips: those within 3 of their edges of where the input passes through itself).
#
# usage: bench/midsize_remesh.sh [EQMESH_BINARY] [SHARED_MESHES_DIR] [OUT_DIR]
# EQMESH_REMESH_ARGS="--base-vertices 400" passes extra options to every remesh;
# EQMESH_MESHES="knot.off.gz dino.off.gz" picks meshes by file name.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
eqmesh="${1:-$here/../build/tools/eqmesh}"
meshes="${2:-$here/../../shared/meshes}"
out_dir="${3:-${TMPDIR:-/tmp}/eqmesh_midsize_remesh}"
extra="${EQMESH_REMESH_ARGS:-}"
mkdir -p "$out_dir"
all=(midsize/knot.off.gz midsize/bones.off.gz midsize/mushroom.off.gz midsize/triceratops.off.gz
     midsize/cow.off.gz midsize/dino.off.gz midsize/femur.off.gz midsize/bull.off.gz
     midsize/lion-head.off.gz midsize/mannequin-devil.off.gz midsize/man.off.gz midsize/bear.off.gz
     midsize/diplodocus.off.gz small/bunny_npm.obj small/fandisk.obj small/skull_low_resolution.obj
     small/rocker-arm.off small/max-planck_10k.obj)
printf '%-26s %7s %6s %4s %8s %7s %7s %6s %6s %7s %7s %s\n' mesh in_V base lvl out_V normal psnr flips x_flips slivers seconds notes
for rel in "${all[@]}"; do
  name=$(basename "$rel")
  if [ -n "${EQMESH_MESHES:-}" ] && [[ " $EQMESH_MESHES " != *" $name "* ]]; then continue; fi
  in="$meshes/$rel"
  [ -f "$in" ] || { echo "$name: missing, skipped"; continue; }
  stem="${name%%.*}"
  # shellcheck disable=SC2086
  if ! json=$("$eqmesh" remesh "$in" "$out_dir/$stem.srm" --json $extra 2>"$out_dir/$stem.err"); then
    echo "$name: FAILED: $(tail -1 "$out_dir/$stem.err")"
    continue
  fi
  printf '%s\n' "$json" > "$out_dir/$stem.json"
  python3 - "$name" "$json" <<'PY'
import json, sys
d = json.loads(sys.argv[2])
psnr = d.get("psnr_db", float("nan"))
if psnr is None:
    psnr = float("inf")  # the remesh is the input's surface (or keeps it exactly)
print("%-26s %7d %6d %4d %8d %7.3f %7.2f %6d %6d %7d %7.2f %s" % (
    sys.argv[1], d["input_vertices"], d["base_vertices"], d["levels"], d["output_vertices"],
    d["normal_fraction"], psnr,
    d.get("flipped_faces", -1) + d.get("degenerate_faces", 0), d.get("flipped_near_self_crossings", -1),
    d.get("sliver_faces", -1),
    d["seconds"], "; ".join(d.get("notes", []))))
PY
done

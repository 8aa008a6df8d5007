#!/usr/bin/env bash
# Remesh quality bench: runs `eqmesh remesh --json` at the default settings on every
# bench mesh (dragon_vrip_res2 excluded: it is a robustness-only input) and prints
# one table row per mesh plus the raw JSON lines.
#
# usage: bench/remesh_quality.sh [EQMESH_BINARY] [MESH_DIR] [OUT_DIR]
# EQMESH_REMESH_RUNS=N (default 1) remeshes each mesh N times and reports the run
# with the median time (the outputs are identical; the VM's speed is not).
# slivers: finest faces of quality 4*sqrt(3)*area / sum(edge^2) below 0.1 (not a bar).
# Quality bars (bench/README_remesh.md): no flipped/degenerate faces, closed input
# -> closed output of the same genus, normal_fraction >= 0.90, psnr_db >= 84,
# <= 30 s per million input triangles.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
eqmesh="${1:-$here/../build/tools/eqmesh}"
mesh_dir="${2:-$here/../../shared/meshes/bench}"
out_dir="${3:-${TMPDIR:-/tmp}/eqmesh_remesh_bench}"
extra="${EQMESH_REMESH_ARGS:-}"
runs="${EQMESH_REMESH_RUNS:-1}"
mkdir -p "$out_dir"
meshes=(stanford-bunny.obj horse.ply armadillo_50k.obj skull_50k.obj igea.ply dragon_vrip.ply.gz)
printf '%-20s %8s %6s %5s %9s %7s %7s %7s %5s %7s %6s %8s %s\n' mesh in_V base lvl out_V normal psnr s/Mtri flips slivers genus time notes
for m in "${meshes[@]}"; do
  in="$mesh_dir/$m"
  [ -f "$in" ] || { echo "$m: missing, skipped"; continue; }
  out="$out_dir/${m%%.*}_remesh.ply"
  jsons=()
  for ((r = 1; r <= runs; r++)); do
    # shellcheck disable=SC2086
    if ! json=$("$eqmesh" remesh "$in" "$out" --json $extra 2>"$out_dir/${m%%.*}.err"); then
      echo "$m: FAILED: $(tail -1 "$out_dir/${m%%.*}.err")"
      continue 2
    fi
    jsons+=("$json")
  done
  printf '%s\n' "${jsons[@]}" > "$out_dir/${m%%.*}.json"
  python3 - "$m" "${jsons[@]}" <<'PY'
import json, sys
m = sys.argv[1]
runs = sorted((json.loads(a) for a in sys.argv[2:]), key=lambda d: d["seconds"])
d = runs[len(runs) // 2]
if len(runs) > 1:
    d.setdefault("notes", []).append("median of %d runs (%.1f-%.1f s)" % (len(runs), runs[0]["seconds"], runs[-1]["seconds"]))
tris = d.get("input_faces") or 2 * d["input_vertices"]
s_per_mtri = d["seconds"] / (tris / 1e6)
genus_ok = d["input_closed_genus"] == d["output_closed_genus"] and d["input_boundary_loops"] == d["output_boundary_loops"]
print("%-20s %8d %6d %5d %9d %7.3f %7.2f %7.1f %5d %7d %6s %8.1f %s" % (
    m, d["input_vertices"], d["base_vertices"], d["levels"], d["output_vertices"], d["normal_fraction"],
    d.get("psnr_db", float("nan")), s_per_mtri, d.get("flipped_faces", -1) + d.get("degenerate_faces", 0),
    d.get("sliver_faces", -1), "ok" if genus_ok else "DIFF", d["seconds"], "; ".join(d.get("notes", []))))
PY
done

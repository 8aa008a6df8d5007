#!/usr/bin/env bash
# Default triangle budget on every mesh (issue #33): `eqmesh encode MESH out.glb
# --psnr D` (the .glb records the source's triangle count), `eqmesh decode out.glb`
# with the loader's default budget, then `eqmesh info` on the input and on the
# decoded mesh. One Markdown row per mesh: input and decoded triangles, whether the
# decoded mesh is manifold, its boundary loops and components against the input's,
# its PSNR, and the encoder's warning when the budget could not carry the floor.
#
# usage: bench/budget_sweep.sh [MESH ...]   (default: ../shared/meshes/midsize/*, small/* and bench/
#                                           horse, stanford-bunny, armadillo_50k, skull_50k)
# env:   EQMESH (default build/tools/eqmesh), PSNR (70)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
eqmesh="${EQMESH:-$root/build/tools/eqmesh}"
shared="$root/../shared/meshes"
psnr_target="${PSNR:-70}"
meshes=("$@")
if ((${#meshes[@]} == 0)); then
  for m in "$shared"/midsize/* "$shared"/small/*; do [[ -f "$m" ]] && meshes+=("$m"); done
  meshes+=("$shared/bench/horse.ply" "$shared/bench/stanford-bunny.obj" "$shared/bench/armadillo_50k.obj"
           "$shared/bench/skull_50k.obj")
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

field() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d.get(sys.argv[2], ""))' "$1" "$2"; }

echo "| mesh | input triangles | decoded triangles | within | manifold | boundary loops (input) | components (input) | PSNR dB | note |"
echo "|---|---|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  name="$(basename "$mesh")"
  echo "budget_sweep.sh: $name" >&2
  "$eqmesh" info "$mesh" --json >"$tmp/in.json"
  if ! "$eqmesh" encode "$mesh" "$tmp/out.glb" --psnr "$psnr_target" --json >"$tmp/enc.json" 2>"$tmp/enc.err"; then
    echo "| $name | $(field "$tmp/in.json" faces) | encode failed: $(tail -1 "$tmp/enc.err") | | | | | | |"
    continue
  fi
  note="$(python3 -c 'import json,sys; print("; ".join(p.get("note","") for p in json.load(open(sys.argv[1]))["primitives"] if p.get("note")))' "$tmp/enc.json")"
  compressed="$(python3 -c 'import json,sys; print(sum(p["compressed"] for p in json.load(open(sys.argv[1]))["primitives"]))' "$tmp/enc.json")"
  [[ "$compressed" == 0 ]] && note="left unchanged: $(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["primitives"][0].get("reason",""))' "$tmp/enc.json")"
  "$eqmesh" decode "$tmp/out.glb" "$tmp/dec.ply" >/dev/null
  "$eqmesh" info "$tmp/dec.ply" --json >"$tmp/dec.json"
  psnr="$("$eqmesh" compare "$mesh" "$tmp/dec.ply" --json | python3 -c 'import json,sys; print("%.2f" % json.load(sys.stdin)["psnr_db"])')"
  in_faces="$(field "$tmp/in.json" faces)"
  out_faces="$(field "$tmp/dec.json" faces)"
  within=$([[ "$out_faces" -le "$in_faces" ]] && echo yes || echo NO)
  echo "| $name | $in_faces | $out_faces | $within | $(field "$tmp/dec.json" manifold) |" \
       "$(field "$tmp/dec.json" boundary_loops) ($(field "$tmp/in.json" boundary_loops)) |" \
       "$(field "$tmp/dec.json" components) ($(field "$tmp/in.json" components)) | $psnr | $note |"
done

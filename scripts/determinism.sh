#!/usr/bin/env bash
# Byte-identical output across compilers and optimisation levels: builds the
# eqmesh tool with gcc and clang at -O0 (Debug) and -O2 (RelWithDebInfo), runs
# the same pipeline with each (remesh to .srm, encode to .eqm and .glb at a bpv
# target, which exercises the rate and level searches and the Metro sampler,
# decode), at 1 and 2 threads, and compares the SHA-256 of every output.
#   scripts/determinism.sh [MESH]   (default samples/meshes/blob.obj)
# Prints one table row per build and exits 1 on any difference.
set -euo pipefail
cd "$(dirname "$0")/.."
MESH="${1:-samples/meshes/blob.obj}"
JOBS="${JOBS:-2}"
WORK="${DETERMINISM_DIR:-build-determinism}"
CONFIGS=("g++ Debug" "g++ RelWithDebInfo" "clang++ Debug" "clang++ RelWithDebInfo")
mkdir -p "$WORK"

build_tool() {  # compiler build_type -> path of eqmesh
  local dir="$WORK/${1%++}-$2"
  cmake -S . -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER="$1" -DCMAKE_BUILD_TYPE="$2" -DEQMESH_BUILD_TESTS=OFF >/dev/null
  cmake --build "$dir" -j "$JOBS" --target eqmesh >/dev/null
  echo "$dir/tools/eqmesh"
}

run_pipeline() {  # eqmesh out_dir threads
  local e="$1" out="$2" t="$3"
  mkdir -p "$out"
  "$e" remesh "$MESH" "$out/mesh.srm" --threads "$t" >/dev/null
  "$e" encode "$out/mesh.srm" "$out/mesh.eqm" --original "$MESH" --bpv 1 --threads "$t" >/dev/null
  "$e" encode "$MESH" "$out/mesh.glb" --bpv 1 --threads "$t" >/dev/null
  "$e" decode "$out/mesh.eqm" "$out/decoded.ply" >/dev/null
}

reference=""
status=0
for config in "${CONFIGS[@]}"; do
  read -r cxx type <<<"$config"
  tool=$(build_tool "$cxx" "$type")
  for threads in 1 2; do
    out="$WORK/out-${cxx%++}-$type-t$threads"
    run_pipeline "$tool" "$out" "$threads"
    digest=$(cd "$out" && sha256sum mesh.srm mesh.eqm mesh.glb decoded.ply | sha256sum | cut -c1-16)
    printf '%-8s %-15s threads %d  %s\n' "${cxx%++}" "$type" "$threads" "$digest"
    if [[ -z "$reference" ]]; then
      reference="$out"
    elif ! (cd "$out" && sha256sum mesh.srm mesh.eqm mesh.glb decoded.ply) | sed "s#  #  $reference/#" |
        (cd . && sha256sum --quiet -c -); then
      echo "determinism: $out differs from $reference" >&2
      status=1
    fi
  done
done
exit "$status"

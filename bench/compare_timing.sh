#!/usr/bin/env bash
# Times `eqmesh compare` at the default sample count on two ~100k-triangle
# meshes: ORIGINAL (default: armadillo_50k, 99,976 faces) against its
# 0.1 %-of-diagonal noisy copy made by `eqmesh perturb`, with 2 threads.
# Whole-process wall time (read + compare) via /usr/bin/time; prints every run
# and the median. Target: median under 10 s on 2 cores.
#
# usage: bench/compare_timing.sh [ORIGINAL]
# env:   EQMESH (default build/tools/eqmesh), RUNS (5), THREADS (2),
#        NOISE (0.001), SAMPLES (empty = the default count)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
eqmesh="${EQMESH:-$root/build/tools/eqmesh}"
original="${1:-$root/../shared/meshes/bench/armadillo_50k.obj}"
runs="${RUNS:-5}"
threads="${THREADS:-2}"
noise="${NOISE:-0.001}"
samples_arg=()
[[ -n "${SAMPLES:-}" ]] && samples_arg=(--samples "$SAMPLES")

[[ -x "$eqmesh" ]] || { echo "compare_timing.sh: no eqmesh binary at $eqmesh (set EQMESH)" >&2; exit 1; }
[[ -r "$original" ]] || { echo "compare_timing.sh: cannot read $original" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "compare_timing.sh: needs /usr/bin/time (Debian package 'time')" >&2; exit 1; }

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
noisy="$tmp/noisy.ply"
"$eqmesh" perturb "$original" "$noisy" --noise "$noise" --seed 1 > /dev/null

echo "eqmesh compare $(basename "$original") vs ${noise} x diagonal noisy copy, $threads threads, $runs runs"
for i in $(seq 1 "$runs"); do
  /usr/bin/time -f "%e %U %M" -o "$tmp/time.$i" \
    "$eqmesh" compare "$original" "$noisy" --threads "$threads" "${samples_arg[@]}" --json > "$tmp/out.$i.json"
  read -r wall user peak < "$tmp/time.$i"
  psnr="$(grep -o '"psnr_db": [^,]*' "$tmp/out.$i.json" | cut -d' ' -f2)"
  samples="$(grep -o '"samples": [0-9]*' "$tmp/out.$i.json" | cut -d' ' -f2)"
  printf 'run %d: %6.2f s wall  %6.2f s user  %7d KiB peak  samples/direction %s  psnr %s dB\n' \
    "$i" "$wall" "$user" "$peak" "$samples" "$psnr"
  echo "$wall" >> "$tmp/walls"
done
median="$(sort -g "$tmp/walls" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')"
echo "median wall: $median s"

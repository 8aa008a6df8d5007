#!/usr/bin/env bash
# libFuzzer targets of fuzz/ (issue 7): build, seed corpora, run.
#
#   scripts/fuzz.sh build              clang build into build-fuzz (-DEQMESH_FUZZ=ON)
#   scripts/fuzz.sh corpus             seed streams, GLBs and mesh files -> build-fuzz/corpus/<target>
#   scripts/fuzz.sh smoke              build + corpus + every target for ~20 s (CI)
#   scripts/fuzz.sh run SECONDS        every target for SECONDS each
#   scripts/fuzz.sh run -runs=N        every target for N executions each
#   scripts/fuzz.sh repro TARGET FILE  run one input through one target
#
# Targets run one after another (one process each), niced. Every run enforces
# -rss_limit_mb=2048 and -malloc_limit_mb (the bounded-allocation rule: no single
# allocation above FUZZ_MALLOC_LIMIT_MB, default 512) and -timeout=FUZZ_TIMEOUT
# (default 10 s per input). Any crash, leak, sanitizer report, timeout or OOM fails
# the script (artifacts in build-fuzz/artifacts/<target>/); executions and corpus
# size are printed per target. FUZZ_TARGETS="eqm_decode read_ply" runs a subset;
# FUZZ_LOG_DIR keeps each target's full log. FUZZ_SEEDS=PATH takes the seed
# generator from another build (every test build has one, in
# tests/fuzz_regressions/): the fuzz build then compiles only the targets and what
# they link, not the encoder (scripts/test.sh passes the sanitizer build's).
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR="${FUZZ_BUILD_DIR:-build-fuzz}"
JOBS="${JOBS:-2}"
ALL_TARGETS=(eqm_decode gltf_load read_obj read_ply read_off)
read -r -a TARGETS <<<"${FUZZ_TARGETS:-${ALL_TARGETS[*]}}"
MALLOC_LIMIT_MB="${FUZZ_MALLOC_LIMIT_MB:-512}"
TIMEOUT_S="${FUZZ_TIMEOUT:-10}"

usage() {
  sed -n '2,/^[^#]/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
  exit 2
}

build() {
  local cxx="${FUZZ_CXX:-clang++}"
  command -v "$cxx" >/dev/null || { echo "fuzz: $cxx not found (apt-get install clang)" >&2; exit 1; }
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
    -DEQMESH_FUZZ=ON -DEQMESH_BUILD_TESTS=OFF >/dev/null
  local targets=()
  [[ -n "${FUZZ_SEEDS:-}" ]] || targets+=(eqmesh_fuzz_seeds)
  for t in "${ALL_TARGETS[@]}"; do targets+=("fuzz_$t"); done
  cmake --build "$BUILD_DIR" -j "$JOBS" --target "${targets[@]}"
}

corpus() {
  local seeds="${FUZZ_SEEDS:-$BUILD_DIR/fuzz/eqmesh_fuzz_seeds}"
  [[ -x "$seeds" ]] || { echo "fuzz: no seed generator at $seeds (scripts/fuzz.sh build)" >&2; exit 1; }
  ASAN_OPTIONS=detect_leaks=0 "$seeds" "$BUILD_DIR/corpus" tests/codec/data/*.eqm
  for t in "${ALL_TARGETS[@]}"; do
    echo "corpus/$t: $(find "$BUILD_DIR/corpus/$t" -type f | wc -l) files"
  done
}

# run_target TARGET LIBFUZZER_ARGS...: prints one summary line, returns non-zero on
# any finding.
run_target() {
  local t="$1"
  shift
  local exe="$BUILD_DIR/fuzz/fuzz_$t"
  local dir="$BUILD_DIR/corpus/$t"
  local artifacts="$BUILD_DIR/artifacts/$t/"
  local log
  log="$(mktemp)"
  mkdir -p "$dir" "$artifacts"
  local start=$SECONDS rc=0
  ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0:${ASAN_OPTIONS:-}" \
  UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}" \
    nice -n 10 "$exe" "$dir" -dict="fuzz/$t.dict" -artifact_prefix="$artifacts" \
      -rss_limit_mb=2048 -malloc_limit_mb="$MALLOC_LIMIT_MB" -timeout="$TIMEOUT_S" \
      -print_final_stats=1 -close_fd_mask=1 "$@" >"$log" 2>&1 || rc=$?
  local wall=$((SECONDS - start))
  local execs
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  [[ -n "$execs" ]] || execs="$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log" | tail -1)"
  local files
  files="$(find "$dir" -type f | wc -l)"
  local rate="?"
  [[ -n "$execs" && "$wall" -gt 0 ]] && rate=$((execs / wall))
  printf '%-11s %12s execs %7ss %9s exec/s  corpus %6s files  %s\n' "$t" "${execs:-?}" "$wall" "$rate" \
    "$files" "$([[ $rc -eq 0 ]] && echo ok || echo "FAILED (rc $rc)")"
  if [[ -n "${FUZZ_LOG_DIR:-}" ]]; then
    mkdir -p "$FUZZ_LOG_DIR"
    cp "$log" "$FUZZ_LOG_DIR/$t.log"
  fi
  if [[ $rc -ne 0 ]]; then
    grep -E "ERROR|WARNING|SUMMARY|eqmesh fuzz check|Test unit written|==[0-9]+==" "$log" | head -40 >&2 || true
    tail -n 30 "$log" >&2
  fi
  rm -f "$log"
  return "$rc"
}

run_all() {
  local failed=0
  for t in "${TARGETS[@]}"; do
    run_target "$t" "$@" || failed=1
  done
  if [[ $failed -ne 0 ]]; then
    echo "fuzz: findings above (inputs in $BUILD_DIR/artifacts/)" >&2
    return 1
  fi
}

cmd="${1:-}"
[[ -n "$cmd" ]] || usage
shift
case "$cmd" in
  build) build ;;
  corpus) corpus ;;
  smoke)
    build
    corpus
    run_all -max_total_time="${FUZZ_SMOKE_SECONDS:-20}"
    ;;
  run)
    arg="${1:-}"
    [[ -n "$arg" ]] || usage
    shift
    if [[ "$arg" == -runs=* ]]; then
      run_all "$arg" "$@"
    else
      run_all -max_total_time="$arg" "$@"
    fi
    ;;
  repro)
    [[ $# -eq 2 ]] || usage
    ASAN_OPTIONS="detect_leaks=1:${ASAN_OPTIONS:-}" UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
      "$BUILD_DIR/fuzz/fuzz_$1" -rss_limit_mb=2048 -malloc_limit_mb="$MALLOC_LIMIT_MB" "$2"
    ;;
  *) usage ;;
esac

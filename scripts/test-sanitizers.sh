#!/usr/bin/env bash
# The GoogleTest suite built with clang at -O1 under AddressSanitizer +
# UndefinedBehaviorSanitizer (LeakSanitizer included), into build-asan. clang
# rather than gcc so that, with the gcc -O2 run of scripts/test.sh, the pinned
# determinism hashes (tests/tools/determinism_test.cpp) are checked on two
# compilers and two optimisation levels (scripts/determinism.sh adds -O0).
# -O1, not -O0: at -O0 the remeshing tests run 10x slower under ASan, past
# CI's budget, and -O1 keeps every check ASan and UBSan make.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
BUILD_DIR="${SANITIZER_BUILD_DIR:-build-asan}"
CC=clang CXX=clang++ BUILD_DIR="$BUILD_DIR" BUILD_TYPE=Debug \
  bash scripts/build.sh -DEQMESH_BUILD_TESTS=ON -DEQMESH_SANITIZE=ON -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" "$@"
# bench_quick (the benchmark script's smoke run: Python driving eqmesh, Draco and
# gltfpack) is left to the plain build: under ASan it took 145 of the stage's 353 s
# on the 2-core CI machine (session 14), and the eqmesh paths it drives are the
# ones the CLI and glTF tests here already run. Remesh.ALevelFewer... remeshes a
# mid-size asset five times over (its level drops, each with its floor and fold
# retries): the hard shapes here run the same stages.
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 1800 \
  -E '^(bench_quick|Remesh\.ALevelFewerWhereTheAutomaticCountFolds)$'

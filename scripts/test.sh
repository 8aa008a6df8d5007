#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds with AddressSanitizer
# and UndefinedBehaviorSanitizer, runs every GoogleTest case through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
BUILD_DIR="${BUILD_DIR:-build-test}" BUILD_TYPE=RelWithDebInfo \
  bash scripts/build.sh -DEQMESH_SANITIZE=ON -DEQMESH_BUILD_TESTS=ON
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "${BUILD_DIR:-build-test}" --output-on-failure -j "$(nproc)" --timeout 900

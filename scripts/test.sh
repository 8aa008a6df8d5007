#!/usr/bin/env bash
# The whole test suite (what .ci/run calls): installs what is missing, then
#   1. builds (gcc, RelWithDebInfo with line tables only, warnings on) and runs
#      every GoogleTest case, then installs the package and builds the C
#      consumer against it (scripts/test-install.sh);
#   2. the web loader in headless Chromium (scripts/test-web.sh);
#   3. the same GoogleTest suite built with clang -O1 under AddressSanitizer +
#      UndefinedBehaviorSanitizer (scripts/test-sanitizers.sh); the pinned
#      determinism hashes are thereby checked on gcc -O2 and clang -O1;
#   4. a short smoke run of every libFuzzer target (scripts/fuzz.sh smoke).
# EQMESH_TEST_STAGES="build web sanitizers fuzz" picks stages (default: all).
set -euo pipefail
cd "$(dirname "$0")/.."
STAGES="${EQMESH_TEST_STAGES:-build web sanitizers fuzz}"
has_stage() { [[ " $STAGES " == *" $1 "* ]]; }
EQMESH_SETUP_TESTS=1 bash scripts/setup-debian.sh
# The Khronos glTF-Validator (npm, pinned in tests/gltf/validator/package-lock.json)
# checks every GLB the glTF tests write; those tests skip when it is absent.
if ! command -v npm >/dev/null 2>&1; then
  EQMESH_SETUP_EXTRAS=1 bash scripts/setup-debian.sh || echo "test: npm unavailable; validator tests will skip"
fi
if command -v npm >/dev/null 2>&1 && [[ ! -d tests/gltf/validator/node_modules ]]; then
  (cd tests/gltf/validator && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "test: npm ci failed; validator tests will skip"
fi
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
BUILD_DIR="${BUILD_DIR:-build-test}"
stage() { echo "== test: $1 ($(date +%T))"; }
if has_stage build; then
  stage "build + GoogleTest ($BUILD_DIR)"
  # Line tables (-g1) are what a failing test's backtrace needs; full debug
  # information made gcc -O2 compiles about a fifth slower (ten of the
  # build's files: 41.8 s with -g, 33.5 s with -g1).
  BUILD_DIR="$BUILD_DIR" BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" \
    bash scripts/build.sh -DEQMESH_BUILD_TESTS=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" "$@"
  ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 900
  stage "installed package and a C consumer"
  BUILD_DIR="$BUILD_DIR" bash scripts/test-install.sh
fi
if has_stage web; then
  stage "web loader in headless Chromium"
  BUILD_DIR="$BUILD_DIR" bash scripts/test-web.sh
fi
if has_stage sanitizers; then
  stage "GoogleTest under ASan + UBSan (clang -O1)"
  bash scripts/test-sanitizers.sh
fi
if has_stage fuzz; then
  stage "libFuzzer smoke run"
  # The sanitizer build's seed generator spares the fuzz build the encoder.
  seeds="${SANITIZER_BUILD_DIR:-build-asan}/tests/fuzz_regressions/eqmesh_fuzz_seeds"
  if [[ -x "$seeds" ]] && has_stage sanitizers; then export FUZZ_SEEDS="$PWD/$seeds"; fi
  FUZZ_SMOKE_SECONDS="${FUZZ_SMOKE_SECONDS:-10}" bash scripts/fuzz.sh smoke
fi
stage "all passed"

#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (RelWithDebInfo, warnings
# on), runs every GoogleTest case through ctest. scripts/test-sanitizers.sh runs the
# same suite under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
# The Khronos glTF-Validator (npm, pinned in tests/gltf/validator/package-lock.json)
# checks every GLB the glTF tests write; those tests skip when it is absent.
if ! command -v npm >/dev/null 2>&1; then
  EQMESH_SETUP_EXTRAS=1 bash scripts/setup-debian.sh || echo "test: npm unavailable; validator tests will skip"
fi
if command -v npm >/dev/null 2>&1 && [[ ! -d tests/gltf/validator/node_modules ]]; then
  (cd tests/gltf/validator && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "test: npm ci failed; validator tests will skip"
fi
BUILD_DIR="${BUILD_DIR:-build-test}"
BUILD_DIR="$BUILD_DIR" BUILD_TYPE="${BUILD_TYPE:-RelWithDebInfo}" \
  bash scripts/build.sh -DEQMESH_BUILD_TESTS=ON "$@"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 900
# The web loader in headless Chromium (skips, saying so, without emcc or chromium).
BUILD_DIR="$BUILD_DIR" bash scripts/test-web.sh

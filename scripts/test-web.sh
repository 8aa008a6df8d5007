#!/usr/bin/env bash
# The web loader's real-browser test (tests/web/): builds the WebAssembly decoder,
# installs three and playwright-core (npm ci, pinned), encodes samples/meshes/blob.obj
# with the native eqmesh tool (EQ and zerotree coders), records the native decoder's
# counts per level, and runs headless Chromium over the demo page. Installs emscripten and chromium when
# missing (EQMESH_SETUP_WEB=1 scripts/setup-debian.sh); skips, saying so, only where
# emcc, chromium or npm is still absent after that.
#   BUILD_DIR  native build holding tools/eqmesh (default build-test; built into
#              build-web-native when it has none); outputs go to BUILD_DIR/web/
set -euo pipefail
cd "$(dirname "$0")/.."
CHROMIUM="${CHROMIUM:-/usr/bin/chromium}"
if ! command -v emcc >/dev/null 2>&1 || [[ ! -x "$CHROMIUM" ]]; then
  EQMESH_SETUP_WEB=1 bash scripts/setup-debian.sh || echo "test-web: could not install emscripten / chromium"
fi
missing=()
command -v emcc >/dev/null 2>&1 || missing+=(emcc)
[[ -x "$CHROMIUM" ]] || missing+=("$CHROMIUM")
command -v npm >/dev/null 2>&1 || missing+=(npm)
if ((${#missing[@]})); then
  echo "test-web: SKIPPED, not installed: ${missing[*]} (EQMESH_SETUP_WEB=1 bash scripts/setup-debian.sh)"
  exit 0
fi
started=$SECONDS
BUILD_DIR="${BUILD_DIR:-build-test}"
EQMESH="${EQMESH:-$BUILD_DIR/tools/eqmesh}"
if [[ ! -x "$EQMESH" ]]; then
  BUILD_DIR=build-web-native JOBS="${JOBS:-2}" bash scripts/build.sh -DEQMESH_BUILD_TESTS=OFF
  EQMESH=build-web-native/tools/eqmesh
fi
WORK="$BUILD_DIR/web"
mkdir -p "$WORK/models"

bash scripts/build-wasm.sh

# npm ci only when the lock file changed since the last install.
for dir in web tests/web; do
  if [[ ! "$dir/node_modules/.package-lock.json" -nt "$dir/package-lock.json" ]]; then
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  fi
done

# The test models (EQ coder, and zerotree, whose levels share one range), their
# .gltf + .bin splits, a corrupt copy, a copy cut short after level 2, and the native
# decoder's counts per level.
model=samples/meshes/blob.obj
encode() {  # NAME EXTRA-ARGS...
  local glb="$WORK/models/$1.glb"
  if [[ ! "$glb" -nt "$EQMESH" || ! "$glb" -nt "$model" ]]; then
    "$EQMESH" encode "$model" "$glb" --bpv 2 "${@:2}" >/dev/null
  fi
  python3 samples/web/split_glb.py "$glb" "$WORK/models/split"
}
encode blob
encode blob_zerotree --coder zerotree
# A textured asset and its compressed copy, which the screenshot test renders from
# the same camera (only where the shared meshes are present; the test skips
# otherwise). The original is copied into the build folder, never into the repo.
duck=../shared/meshes/textured/duck.glb
if [[ -f "$duck" ]]; then
  cp "$duck" "$WORK/models/duck_original.glb"
  if [[ ! "$WORK/models/duck.glb" -nt "$EQMESH" ]]; then
    "$EQMESH" encode "$duck" "$WORK/models/duck.glb" --psnr 70 >/dev/null
  fi
fi
python3 samples/web/split_glb.py --corrupt-magic "$WORK/models/blob.glb" "$WORK/corrupt.glb"
python3 samples/web/split_glb.py --cut-after-level 2 "$WORK/models/blob.glb" "$WORK/models/split"
python3 - "$EQMESH" "$WORK" blob blob_zerotree <<'EOF'
import json, os, subprocess, sys
eqmesh, work, names = sys.argv[1], sys.argv[2], sys.argv[3:]
def decode(name, level):
    out = subprocess.run([eqmesh, "decode", f"{work}/models/{name}.glb", f"{work}/native_level.ply",
                          "--level", str(level), "--json"], check=True, capture_output=True, text=True).stdout
    report = json.loads(out)
    return {"vertices": report["vertices"], "triangles": report["faces"]}
def levels(name):
    gltf = json.load(open(f"{work}/models/split/{name}.gltf"))
    return gltf["meshes"][0]["primitives"][0]["extensions"]["EXT_normal_mesh_compression"]["levels"]
native = {n: {"levels": levels(n), "counts": [decode(n, k) for k in range(levels(n) + 1)]} for n in names}
json.dump(native, open(f"{work}/native.json", "w"))
os.remove(f"{work}/native_level.ply")
EOF

# Streams coded as is in surface frames (ext_spec A.6.1): the WASM decoder must
# give the native decoder's positions bit for bit.
for target in 55 70; do
  "$EQMESH" encode "$model" "$WORK/as_is_$target.eqm" --levels 0 --base-vertices 1000000 --psnr "$target" >/dev/null
  "$EQMESH" decode "$WORK/as_is_$target.eqm" "$WORK/as_is_$target.obj" >/dev/null
done
node tests/web/frames_match_native.mjs "${WASM_BUILD_DIR:-build-wasm}" \
  "$WORK/as_is_55.eqm:$WORK/as_is_55.obj" "$WORK/as_is_70.eqm:$WORK/as_is_70.obj"

EQMESH_WEB_WORK="$WORK" node --test --test-reporter=spec tests/web/
echo "test-web: screenshots $WORK/screenshot*.png; wall time $((SECONDS - started)) s"

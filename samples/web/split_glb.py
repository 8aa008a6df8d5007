#!/usr/bin/env python3
"""Splits a .glb into NAME.gltf + NAME.bin, so that a browser can fetch the
EXT_normal_mesh_compression stream level by level with HTTP Range requests (a
GLB arrives in one piece: GLTFLoader fetches the whole file before parsing).
Also writes corrupt copies for the web test. Standard library only.

  split_glb.py IN.glb OUT_DIR            -> OUT_DIR/NAME.gltf, OUT_DIR/NAME.bin
  split_glb.py --corrupt-magic IN OUT    -> OUT: IN with the first stream's magic broken
  split_glb.py --stream IN.glb OUT.eqm   -> OUT.eqm: the first compressed stream alone
  split_glb.py --cut-after-level K IN.glb OUT_DIR
                                         -> OUT_DIR/NAME_cut.gltf + .bin, the .bin ending
                                            inside the first stream's level K+1 chunk
"""
import json
import os
import struct
import sys

EXTENSION = "EXT_normal_mesh_compression"
GLB_MAGIC, JSON_CHUNK, BIN_CHUNK = 0x46546C67, 0x4E4F534A, 0x004E4942


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != GLB_MAGIC or version != 2 or length != len(data):
        sys.exit(f"{path}: not a glTF 2.0 binary file")
    chunks, offset = {}, 12
    while offset + 8 <= length:
        size, kind = struct.unpack_from("<II", data, offset)
        chunks[kind] = (offset + 8, size)
        offset += 8 + ((size + 3) & ~3)
    if JSON_CHUNK not in chunks:
        sys.exit(f"{path}: no JSON chunk")
    start, size = chunks[JSON_CHUNK]
    gltf = json.loads(data[start:start + size])
    return data, gltf, chunks.get(BIN_CHUNK)


def first_stream_offset(gltf, bin_chunk):
    """Offset in the file of the first compressed primitive's stream."""
    for mesh in gltf.get("meshes", []):
        for primitive in mesh["primitives"]:
            ext = primitive.get("extensions", {}).get(EXTENSION)
            if ext is not None:
                view = gltf["bufferViews"][ext["bufferView"]]
                return bin_chunk[0] + view.get("byteOffset", 0), view["byteLength"]
    sys.exit(f"no {EXTENSION} primitive")


def split(path, out_dir):
    data, gltf, bin_chunk = read_glb(path)
    name = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(out_dir, exist_ok=True)
    if bin_chunk is not None:
        start, size = bin_chunk
        with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
            f.write(data[start:start + size])
        gltf["buffers"][0]["uri"] = name + ".bin"
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(gltf, f, separators=(",", ":"))


def corrupt_magic(path, out):
    data, gltf, bin_chunk = read_glb(path)
    offset, _ = first_stream_offset(gltf, bin_chunk)
    broken = bytearray(data)
    broken[offset:offset + 4] = b"XXXX"
    with open(out, "wb") as f:
        f.write(broken)


def extract_stream(path, out):
    data, gltf, bin_chunk = read_glb(path)
    offset, size = first_stream_offset(gltf, bin_chunk)
    with open(out, "wb") as f:
        f.write(data[offset:offset + size])


def cut_after_level(level, path, out_dir):
    data, gltf, bin_chunk = read_glb(path)
    offset, _ = first_stream_offset(gltf, bin_chunk)
    ranges = next(p["extensions"][EXTENSION]["levelByteRanges"] for m in gltf["meshes"]
                  for p in m["primitives"] if EXTENSION in p.get("extensions", {}))
    start, length = ranges[level + 1]
    end = offset + start + length // 2 - bin_chunk[0]
    name = os.path.splitext(os.path.basename(path))[0] + "_cut"
    with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
        f.write(data[bin_chunk[0]:bin_chunk[0] + end])
    gltf["buffers"][0]["uri"] = name + ".bin"
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(gltf, f, separators=(",", ":"))


def main(argv):
    if len(argv) == 3 and not argv[1].startswith("--"):
        split(argv[1], argv[2])
    elif len(argv) == 4 and argv[1] == "--corrupt-magic":
        corrupt_magic(argv[2], argv[3])
    elif len(argv) == 4 and argv[1] == "--stream":
        extract_stream(argv[2], argv[3])
    elif len(argv) == 5 and argv[1] == "--cut-after-level":
        cut_after_level(int(argv[2]), argv[3], argv[4])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)

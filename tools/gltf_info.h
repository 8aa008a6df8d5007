// `eqmesh info` on a glTF that carries EXT_normal_mesh_compression: which
// primitives are compressed, each stream's levels and byte prefixes (from the
// extension object, checked against the stream header), and the decoded
// geometry for the usual diagnosis.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh::cli {

struct GltfPrimitiveInfo {
  int mesh = 0, primitive = 0;
  bool compressed = false;
  // Compressed primitives: the stream's bytes, levels, coder, and the bytes a
  // progressive loader needs for each level 0..levels.
  uint64_t stream_bytes = 0;
  int levels = 0;
  std::string coder;
  std::vector<uint64_t> prefix_bytes;
  // Geometry after decoding every level (compressed) or as stored.
  uint64_t vertices = 0, triangles = 0;
};

struct CompressedGltf {
  std::vector<GltfPrimitiveInfo> primitives;
  Mesh decoded;  // every triangle primitive in world space, all levels decoded
};

// Whether `path` is a .gltf / .glb (by name or magic) whose extensionsUsed lists
// EXT_normal_mesh_compression. Reads the file; false when it cannot.
bool IsCompressedGltf(const std::string& path);

// Reads, checks and decodes such a file. Errors name the file and the primitive.
StatusOr<CompressedGltf> ReadCompressedGltf(const std::string& path);

// ReadMesh, except that a glTF with EXT_normal_mesh_compression is decoded
// (every level) first: what `compare` and `convert` take as input.
StatusOr<Mesh> ReadMeshDecodingGltf(const std::string& path, ReadReport* report = nullptr);

}  // namespace eqmesh::cli

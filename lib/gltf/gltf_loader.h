// Loader for EXT_normal_mesh_compression: reads a .gltf / .glb, decodes every
// compressed primitive and returns a plain glTF 2.0 model any engine can consume.
//
// For each primitive carrying the extension the loader checks the spec's validity
// rules, decodes the stream (only the bytes up to the requested level), writes
// float32 POSITION, unit NORMAL (area-weighted, ext_spec "Reconstruction of
// normals") and indices into new buffer views, repoints the primitive's accessors,
// and removes the extension. Stream bytes and fallback data are dropped, and the
// extension leaves extensionsUsed / extensionsRequired. Everything else (nodes,
// materials, images, animations, other extensions, extras) is kept.
//
// Safe for untrusted files: any problem is a Status naming the file and the
// primitive ("scan.glb: mesh 2 primitive 0: corrupt stream: ..."), never a crash
// and never a silently skipped primitive.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include "core/status.h"
#include "gltf/stream_decoder.h"
#include "mesh/mesh.h"

namespace eqmesh::gltf {

struct LoadOptions {
  // Finest level to decode: -1 = every level of each stream; K >= 0 decodes
  // min(K, levels) and reads only the bytes that level needs.
  int max_level = -1;
  // Triangle budget of each decoded primitive: -1: the extension's triangleBudget
  // (the source's triangle count, when the encoder recorded it; else none); 0:
  // none; N: N. Levels heavier than it are cut down adaptively
  // (DecodeOptions::max_triangles).
  int64_t max_triangles = -1;
  // Stream decoder; empty = the eqmesh codec. Tests substitute a stand-in.
  StreamDecoderFn decoder;
};

struct PrimitiveLoad {
  int mesh = 0;
  int primitive = 0;
  int levels_in_stream = 0;
  int level_decoded = 0;
  uint64_t stream_bytes_read = 0;
  size_t vertices = 0;
  size_t triangles = 0;
};

struct LoadReport {
  std::vector<PrimitiveLoad> decoded;  // one per compressed primitive, in mesh order
};

StatusOr<tinygltf::Model> LoadGltf(const std::string& path, const LoadOptions& options = {},
                                   LoadReport* report = nullptr);

// Same on bytes in memory; `name_for_errors` prefixes messages.
StatusOr<tinygltf::Model> LoadGltfFromBytes(const std::vector<uint8_t>& bytes,
                                            const std::string& name_for_errors,
                                            const LoadOptions& options = {},
                                            LoadReport* report = nullptr);

// The decoding step alone, on a model already read (for example by an engine's own
// tinygltf call with an image loader of its choice).
Status DecodeCompressedPrimitives(tinygltf::Model* model, const LoadOptions& options = {},
                                  LoadReport* report = nullptr);

// Writes a (decoded) model as a self-contained .glb.
Status WriteDecodedGlb(const tinygltf::Model& model, const std::string& path);

// All TRIANGLES primitives of the model's default scene (every root node when no
// scene is given) in world space, node transforms applied, as one Mesh for OBJ / PLY
// output. Compressed primitives must have been decoded first. A node graph that is
// not a forest (a node reached twice) is a parse error; instancing beyond 64
// flattened vertices + faces per buffer byte (at least 2^24) is a resource limit.
StatusOr<Mesh> FlattenToMesh(const tinygltf::Model& model);

// The walk FlattenToMesh makes: every TRIANGLES primitive of the default scene
// with its world transform and a label ("mesh 2 primitive 0"), in scene order.
using PrimitiveVisitor =
    std::function<Status(const tinygltf::Primitive& primitive, const std::string& label, const Eigen::Affine3d& world)>;
Status VisitScenePrimitives(const tinygltf::Model& model, const PrimitiveVisitor& visit);
// FlattenToMesh's instancing rule: the vertices + faces a flattened scene may
// hold, and the charge of one more part against it.
uint64_t FlattenBudget(const tinygltf::Model& model);
Status SpendBudget(uint64_t cost, uint64_t* budget);
// Appends `part` moved by `world` to `out`.
void AppendTransformed(const Mesh& part, const Eigen::Affine3d& world, Mesh* out);

}  // namespace eqmesh::gltf

// Geometry in and out of glTF accessors: reading a primitive's POSITION and indices
// (bounds-checked, for untrusted files), and describing / storing decoded geometry
// as float32 POSITION, unit NORMAL and UNSIGNED_SHORT / UNSIGNED_INT indices.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh::gltf {

// Float VEC3 accessor data (no sparse); `what` names it in errors.
StatusOr<std::vector<Vec3>> ReadVec3Accessor(const tinygltf::Model& model, int accessor,
                                             const std::string& what);

// TEXCOORD data: float, or normalized unsigned byte / short, VEC2 (no sparse).
StatusOr<std::vector<std::array<double, 2>>> ReadTexcoordAccessor(const tinygltf::Model& model, int accessor,
                                                                   const std::string& what);

// TANGENT data (float VEC4: xyz and the handedness w), no sparse.
StatusOr<std::vector<std::array<double, 4>>> ReadTangentAccessor(const tinygltf::Model& model, int accessor);

// COLOR data (VEC3 or VEC4; RGB returned): float, or normalized unsigned byte /
// short, no sparse.
StatusOr<std::vector<std::array<double, 3>>> ReadColorAccessor(const tinygltf::Model& model, int accessor,
                                                                const std::string& what);

// Unsigned SCALAR index data (u8 / u16 / u32), each index < vertex_count.
StatusOr<std::vector<uint32_t>> ReadIndexAccessor(const tinygltf::Model& model, int accessor,
                                                  size_t vertex_count);

// POSITION and indices of a TRIANGLES primitive in mesh-local space (sequential
// indices when it has none). Vertices are kept as stored, unreferenced ones included.
StatusOr<Mesh> ReadTrianglePrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive);

// Accessor indices a compressed or decoded primitive's geometry lives in.
struct GeometryAccessors {
  int position = -1;
  int normal = -1;  // -1: the primitive has no NORMAL
  int indices = -1;
  int texcoord = -1;  // -1: the primitive has no TEXCOORD_0
};

// What WriteGeometry stores: positions and faces, per-vertex unit normals (null:
// the spec's rule on `mesh`) and TEXCOORD_0 (null: none).
struct GeometryData {
  const Mesh* mesh = nullptr;
  const std::vector<Vec3>* normals = nullptr;
  const std::vector<std::array<float, 2>>* texcoords = nullptr;
};

// Sets type, component type, count and (for POSITION) float32 min / max of the three
// accessors from `mesh`. With `store_data` the bytes are appended as new buffer
// views and the accessors point at them; otherwise they become placeholders with no
// bufferView. Returns the buffer views created. Fails on an empty mesh (glTF forbids
// empty accessors) or coordinates beyond float range.
StatusOr<std::vector<int>> WriteGeometry(tinygltf::Model* model, const Mesh& mesh,
                                         const GeometryAccessors& accessors, bool store_data);
// Same with given normals and TEXCOORD_0 (written to accessors.texcoord).
StatusOr<std::vector<int>> WriteGeometry(tinygltf::Model* model, const GeometryData& data,
                                         const GeometryAccessors& accessors, bool store_data);

// A one-mesh, one-node scene holding `mesh` (positions, normals, indices).
StatusOr<tinygltf::Model> ModelFromMesh(const Mesh& mesh);

}  // namespace eqmesh::gltf

// Tangent frames for moving a tangent-space normal map from one parameterization
// to another (texture_transfer.h). glTF asks engines without a TANGENT attribute
// for MikkTSpace frames (Mikkelsen, "Simulation of wrinkled surfaces revisited",
// 2008); this follows its construction in its common simplified form: per face
// the derivative of position along u (and v for the handedness), area-weighted at
// each vertex, made orthogonal to the vertex normal. Departure: no splitting of
// vertices whose faces disagree in handedness, so frames near mirrored UV seams
// are averaged rather than split.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace eqmesh::texture {

using Vec4 = Eigen::Vector4d;

// Unit tangent (xyz) and handedness w = +-1 per vertex: bitangent = w * (normal x
// tangent), as glTF's TANGENT. `normals` are unit vertex normals.
std::vector<Vec4> VertexTangents(const Mesh& mesh, const std::vector<std::array<double, 2>>& texcoords,
                                 const std::vector<Vec3>& normals);

// The orthonormal frame (tangent, bitangent, normal) at barycentric `b` of face
// `f`, interpolated from per-vertex tangents and normals.
struct Frame {
  Vec3 t, b, n;
};
Frame FrameAt(const Mesh& mesh, const std::vector<Vec4>& tangents, const std::vector<Vec3>& normals, uint32_t face,
              const std::array<float, 3>& barycentric);

}  // namespace eqmesh::texture

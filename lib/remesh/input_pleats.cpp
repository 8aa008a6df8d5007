// Pleats of the input surface (input_pleats.h).
#include "remesh/input_pleats.h"

namespace eqmesh {
namespace {

// Adds to `out` the faces sharing a vertex with a face flagged in `in`.
void GrowByOneRing(const Mesh& mesh, const std::vector<uint32_t>& face_offsets,
                   const std::vector<uint32_t>& vertex_faces, const std::vector<uint8_t>& in,
                   std::vector<uint8_t>* out) {
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    if (!in[f]) continue;
    for (uint32_t v : mesh.faces[f]) {
      for (uint32_t q = face_offsets[v]; q < face_offsets[v + 1]; ++q) (*out)[vertex_faces[q]] = 1;
    }
  }
}

}  // namespace

std::vector<uint8_t> FacesNearPleats(const Mesh& mesh, const std::vector<Vec3>& face_normals,
                                     const std::vector<uint32_t>& face_offsets,
                                     const std::vector<uint32_t>& vertex_faces, int rings) {
  std::vector<uint8_t> near(mesh.faces.size(), 0);
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t v : mesh.faces[f]) {
      for (uint32_t q = face_offsets[v]; q < face_offsets[v + 1] && !near[f]; ++q) {
        near[f] = face_normals[f].dot(face_normals[vertex_faces[q]]) < 0.0;
      }
    }
  }
  for (int r = 0; r < rings; ++r) {
    std::vector<uint8_t> grown = near;
    GrowByOneRing(mesh, face_offsets, vertex_faces, near, &grown);
    near = std::move(grown);
  }
  return near;
}

}  // namespace eqmesh

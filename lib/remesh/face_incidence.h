// Vertex -> incident faces of a triangle list, in compressed rows: the faces
// of vertex v are faces[offsets[v] .. offsets[v+1]), in increasing order.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh {

struct FaceIncidence {
  std::vector<uint32_t> offsets;  // num_vertices + 1 entries
  std::vector<uint32_t> faces;
};

inline FaceIncidence BuildFaceIncidence(const std::vector<Face>& faces, size_t num_vertices) {
  FaceIncidence out;
  out.offsets.assign(num_vertices + 1, 0);
  for (const Face& t : faces) {
    for (uint32_t v : t) ++out.offsets[v + 1];
  }
  for (size_t v = 0; v < num_vertices; ++v) out.offsets[v + 1] += out.offsets[v];
  out.faces.resize(out.offsets.back());
  std::vector<uint32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (uint32_t v : faces[f]) out.faces[fill[v]++] = f;
  }
  return out;
}

}  // namespace eqmesh

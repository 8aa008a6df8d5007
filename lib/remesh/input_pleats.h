// Input triangles near a pleat of the input itself, for the refiner's fold scan
// (placement_repair.cpp). Internal to lib/remesh.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh {

// Scanned and decimated inputs fold over on themselves in places (armadillo_50k:
// 91 edges whose two triangles face more than 90 degrees apart, 24 of them
// beyond 154 degrees). A remesh face over such a pleat can face away from the
// input at its centroid although the input under each of its corners faces its
// way. Flags every triangle with a vertex-neighbour facing away from it, then
// every triangle within `rings` vertex-rings of one flagged so.
// `face_normals`: FaceCrossProducts(mesh); `face_offsets` / `vertex_faces`:
// vertex -> incident faces (CSR).
std::vector<uint8_t> FacesNearPleats(const Mesh& mesh, const std::vector<Vec3>& face_normals,
                                     const std::vector<uint32_t>& face_offsets,
                                     const std::vector<uint32_t>& vertex_faces, int rings);

}  // namespace eqmesh

// Renumbering a semi-regular mesh onto a new base-vertex order and base face list
// (the order the base-mesh chunk decodes to), keeping the surface unchanged.
//
// The refinement rules of mesh/semi_regular.h number odd vertices by the order in
// which base faces are walked, so a new base order changes every level's numbering.
// An odd vertex is identified by its parent edge's endpoints, so the positions are
// re-indexed level by level with an edge lookup.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// new base vertex i is old base vertex new_to_old_base[i]; new_base_faces must be
// the old base faces (in any order / corner rotation) in new numbering. Fails if an
// edge of the new hierarchy has no counterpart in the old one.
StatusOr<SemiRegularMesh> RenumberToBase(const SemiRegularMesh& mesh,
                                         const std::vector<uint32_t>& new_to_old_base,
                                         std::vector<Face> new_base_faces);

}  // namespace eqmesh

// Fold removal on the finest level of a remesh, after the last refinement.
//
// Departure from Guskov et al. 2000 (whose remesh has no such pass): a face of
// the finest level that faces away from the input (quality_checks.h) gets its
// finest-level corners moved, one at a time, to the input point closest to
// their neighbours' centroid (same-facing input triangles only), when that
// folds fewer of the faces around them. No parameter is needed any more at the
// finest level, so the move is free in 3D; a moved vertex becomes non-normal.
// Coarser vertices and boundary vertices never move.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/semi_regular.h"
#include "remesh/piercing.h"

namespace eqmesh {

// `folded`: the finest faces that fold (LevelStats::folded_faces of the last
// refinement). Returns how many normal vertices it moved (non-normal now).
size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const std::vector<uint32_t>& folded, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds);

}  // namespace eqmesh

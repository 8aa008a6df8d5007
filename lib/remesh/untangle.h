// Fold removal on the finest level of a remesh, after the last refinement.
//
// Departure from Guskov et al. 2000 (whose remesh has no such pass): a face of
// the finest level that faces away from the input (quality_checks.h) gets its
// corners of the last two levels moved, one at a time, to the input point
// closest to (or half-way to) their neighbours' centroid on same-facing input
// triangles, when that folds fewer of the faces around them; clusters where no
// single move helps are smoothed together. No parameter is needed any more, so
// the moves are free in 3D; moved vertices, and the finest vertices predicted
// from them, become non-normal. Boundary and base vertices never move.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/semi_regular.h"
#include "remesh/piercing.h"

namespace eqmesh {

// `folded`: the finest faces that fold (LevelStats::folded_faces of the last
// refinement). Returns how many normal vertices became non-normal.
size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const std::vector<uint32_t>& folded, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds);

}  // namespace eqmesh

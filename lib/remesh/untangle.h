// Fold removal on the finest level of a remesh, after the last refinement.
//
// Departure from Guskov et al. 2000 (whose remesh has no such pass): a face of
// the finest level that faces away from the input (quality_checks.h) gets its
// corners moved, one at a time, to the input point closest to (or part-way to)
// their neighbours' centroid on same-facing input triangles, or to the blend
// itself where no surface point helps, when that folds fewer of the faces around
// them; clusters where no single move helps are smoothed together. Boundary
// vertices slide along the input's boundary curves (to the closest boundary point
// of their boundary neighbours' midpoint); base vertices never move. Corners of
// every level may move (most folds have a corner from a coarser level than the
// last two), as deep as keeps the normal share >= 0.90: each depth is tried from
// the remesh as it came, all levels first, the last two levels always allowed.
// No parameter is needed any more, so the moves are free in 3D; moved vertices,
// and every later vertex whose butterfly prediction or frame they enter, become
// non-normal.
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

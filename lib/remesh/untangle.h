// Fold removal on the finest level of a remesh. Remesh() runs it after every
// refinement, on the level just pierced, so each level is pierced from an
// unfolded one (remesh.cpp, UntangleNewLevel).
//
// Departure from Guskov et al. 2000 (whose remesh has no such pass): a face of
// the finest level that faces away from the input (quality_checks.h) gets its
// corners moved, one at a time, towards their neighbours' centroid or towards
// the centre of their fan's kernel (fan_kernel.h, after Freitag & Plassmann's
// untangling), in steps, each projected onto same-facing input triangles, or
// the blend itself where no surface point helps, when that folds fewer of the
// faces around them. Clusters where no single move helps (whole folded patches:
// a coarse face turned over with all its descendants) are smoothed together,
// by centroids (Jacobi) or by kernel centres (Gauss-Seidel), in rings widened
// from 2 to 6 around the folds, keeping the best sweep. A move's error may grow
// 2x, or to a floor (centroids 5 % of an edge off the input), since a fold lying
// flat in one input triangle has error 0. Boundary vertices slide along the
// input's boundary curves; base vertices never move. Corners of every level may
// move, as deep as keeps the normal share >= 0.90 (0.80 in the final pass: a
// fold it leaves stays in the remesh, while a non-normal vertex costs only two
// more coefficients): each depth is tried from the remesh as it came, all levels
// first; the finest level alone comes last, its moves stopped where the share
// would reach the floor. A remesh already below the floor (dragon_vrip's) gets
// its last two levels untangled freely. Moves are free in
// 3D; moved vertices, and every later vertex whose butterfly prediction or frame
// they enter, become non-normal. What still folds then gets its coarse patch
// refilled (patch_flattening.h), unless that takes the normal share below the floor.
// Sweeps and refills can fold faces the moves never looked at (they start from
// the refinement's folds), so the moves run again, at every level, seeded with
// what folds then, round after round while that shrinks and the share stays at
// the floor.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/semi_regular.h"
#include "remesh/piercing.h"

namespace eqmesh {

// What the untangled level is for. One that more levels will be pierced from
// keeps its boundary vertices where they are (the next level's boundary
// midpoints are placed by the input's parameters between them) and moves
// vertices only to points of the input: it is the finest level's vertices too,
// and a coarse face's error allowance would leave them far off the surface.
enum class LevelUse { kPiercedFrom, kFinal };

// `folded`: the finest faces that fold (LevelStats::folded_faces of the last
// refinement). `built`: the refinement's butterfly stencils, level by level
// (any prefix, also none; the rest are built when needed). `still_folded`,
// when given, gets the faces that fold afterwards among those it looked at.
// Returns how many normal vertices became non-normal.
size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const RemeshParts& parts, const std::vector<uint32_t>& folded,
                           const std::vector<StencilTable>& built, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds,
                           LevelUse use = LevelUse::kFinal,
                           std::vector<uint32_t>* still_folded = nullptr);

}  // namespace eqmesh

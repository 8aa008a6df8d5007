// Last resort for the folds the untangler leaves: refill the coarse patch
// around them as refinement with zero details would.
//
// Departure from Guskov et al. 2000 (whose remesh has no fold repair). A finest
// face that still faces away from the input after the untangling (untangle.h)
// lies inside one face P of a coarser level. When P itself does not fold, every
// vertex refinement created inside P or on its edges is put, coarse to fine,
// at its butterfly prediction (the subdivision surface, which follows the
// input's curvature), or failing that at its edge's midpoint (P's own linear
// subdivision: coplanar with P and turned as P is, so none of it folds).
// Vertices on P's edges are shared with the neighbouring patches, so a refill
// is kept only when it folds fewer of all the faces around the moved vertices,
// and only when every moved vertex stays within half a finest edge of the input
// (a refill that leaves the surface costs more than the fold: measured on
// skull_50k, a bound of one edge fixes 2 more folds and takes 0.23 dB off the
// remesh, half an edge none). Parents one level above the finest are tried
// first, then up to two levels coarser; three rounds look again at the faces
// a refill changed. The moved vertices, and every later vertex whose prediction
// or frame a moved coarse vertex enters, become non-normal (the caller marks
// them). Patches holding a boundary vertex are not refilled (it would leave the
// input's boundary curve).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/semi_regular.h"
#include "remesh/face_incidence.h"
#include "remesh/piercing.h"
#include "remesh/stencil_cache.h"

namespace eqmesh {

// `candidates`: finest faces that may fold (the rest are known not to);
// `finest_faces`: the finest level's vertex -> faces incidence.
// Moves vertices of `positions` (all levels, finest-level numbering) and
// returns which vertices moved.
std::vector<uint8_t> FlattenFoldedPatches(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                                          const RemeshParts& parts, const std::vector<VertexKind>& kinds,
                                          const std::vector<uint32_t>& candidates, const FaceIncidence& finest_faces,
                                          StencilCache* stencils, std::vector<Vec3>* positions);

}  // namespace eqmesh

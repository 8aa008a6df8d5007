// Base domain of the remesh: a coarse mesh whose vertices are input vertices,
// plus a bijective parameterization of the input over it (one ParamPoint per
// input vertex), built by MAPS-style simplification.
//
// Follows Lee, Sweldens, Schröder, Cowsar, Dobkin, "MAPS" (SIGGRAPH 1998): each
// removal flattens the removed vertex's 1-ring with the conformal z^a map,
// retriangulates it, and relocates every input vertex already mapped into the
// star by point location in that flat chart.
// Departures:
//  * Removal is a half-edge collapse (v into a ring neighbour u), so the new
//    triangulation is the fan from u and base vertices stay input vertices; the
//    order is a greedy priority queue instead of levels of maximal independent
//    sets. Its cost (base_domain.cpp, Candidates) is the largest distance an
//    input vertex of the star would end up from its image on the new fan,
//    divided by the cube of the fan's worst triangle quality, standing in for
//    MAPS's area + curvature weights: quadric error (Garland & Heckbert 1997)
//    removes small protrusions first and leaves slivers along cylinders, and
//    both cost the remesh 5-15 dB at claws, ears and legs.
//  * The simplification stops where the base could no longer carry the
//    surface, not at a vertex count: a collapse is refused when an input
//    vertex of its star would end up farther than a bound (a share of its
//    component's diagonal) from its image on the new fan. Collapses across a
//    thin part, around a handle or over a protrusion move vertices by about
//    its size, so those regions keep their base vertices while flat and gently
//    curved regions simplify on; the base size is an outcome (Remesh reports
//    it). This is the simplification envelope of Cohen et al. (SIGGRAPH 1996)
//    measured through the MAPS map instead of by offset surfaces. The bound
//    may be scaled per input vertex (BaseDomainOptions::bound_scale): Remesh()
//    tightens it over base faces whose remesh still folded.
//  * A collapse must pass the link condition, keep valences in [3, 12], keep
//    every boundary loop at >= 3 vertices, give positively oriented fan
//    triangles in the flat chart, not turn any face by more than ~80° in 3D, and
//    not create a triangle that faces away from the input (the remesh's fold
//    test, quality_checks.h), nor one whose input vertices face away from it.
//  * Interior base vertices of valence 3 at tips (their faces' angles summing
//    to under 300°) get an opposite edge flipped when that is valid
//    (base_domain.cpp, RaiseValenceThree): they seed almost every fold the
//    untangler cannot remove.
//  * Boundary vertices (half-disc map) collapse only along their boundary, and
//    input boundary vertices are kept exactly on base boundary edges.
//  * No parameter smoothing (MAPS §3.4): Tutte smoothing of the base map costs
//    10-60 dB (the domain has too few fixed points for it to stay fair).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/triangle_bvh.h"
#include "remesh/param_point.h"

namespace eqmesh {

struct BaseDomain {
  std::vector<uint32_t> base_to_input;  // input vertex of each base vertex
  std::vector<Face> faces;              // base faces (indices into base_to_input)
  std::vector<ParamPoint> params;       // per input vertex: base face + barycentric
};

struct BaseDomainOptions {
  // Stop once this few vertices remain (or no collapse is allowed).
  size_t target_vertices = 0;
  // A collapse may not take any input vertex farther than this share of its
  // component's bounding-box diagonal from its image on the base. 0: no bound.
  double max_error_share = 0.0;
  // Per input vertex, a factor on that bound (empty: 1 everywhere): Remesh()
  // tightens it where a remesh still folded (remesh.cpp).
  std::vector<double> bound_scale;
  // Flip an edge opposite each valence-3 tip (the departure above). Off for
  // a base no level will refine (Remesh with levels 0): the flips serve the
  // refinement only, and a base of every input vertex must then be the input
  // itself (the encoder's as-is representation).
  bool raise_valence_three = true;
  ProgressFn progress;
};

// `mesh` must be clean: manifold, consistently oriented, every vertex referenced;
// `bvh` is built from it. `is_boundary[v]` marks input boundary vertices.
StatusOr<BaseDomain> BuildBaseDomain(const Mesh& mesh, const TriangleBvh& bvh,
                                     const std::vector<uint8_t>& is_boundary, const BaseDomainOptions& options);

}  // namespace eqmesh

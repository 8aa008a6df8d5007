// Quadric-error simplification of a mesh, for the as-is representation at
// fewer vertices (coding/representation_choice.h): a low-poly asset at 70 dB
// often has more vertices than its error needs, and every vertex it keeps costs
// the as-is stream a position.
//
// Follows Garland & Heckbert, "Surface Simplification Using Quadric Error
// Metrics" (SIGGRAPH 1997): each vertex carries the area-weighted sum of its
// faces' plane quadrics, and the cheapest collapse by that error goes first.
// Departures:
//  * Half-edge collapses only (v into a neighbour u, which keeps its position),
//    as in meshoptimizer's simplifier: the result's vertices are input vertices.
//  * Boundary vertices are never removed, so holes and open rims keep their
//    outlines exactly.
//  * A collapse is refused where it breaks the link condition (the two
//    vertices share neighbours other than the two opposite their edge), leaves
//    a vertex with fewer than three neighbours, or turns one of the moved faces
//    by more than kMaxTurnDegrees or to zero area: the result stays a manifold,
//    consistently oriented mesh of the same topology.
#pragma once

#include <cstddef>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// `mesh`: manifold and consistently oriented, every vertex referenced (what the
// remesher's preparation leaves). Collapses until `target_vertices` remain or no
// collapse is allowed; vertices keep their relative order.
StatusOr<Mesh> SimplifyByQuadrics(const Mesh& mesh, size_t target_vertices);

}  // namespace eqmesh

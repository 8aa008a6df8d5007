// The most interior point of a vertex fan's kernel, in a plane.
//
// Follows the untangling idea of Freitag & Plassmann ("Local optimization-based
// untangling algorithms for quadrilateral meshes", 2001) for triangles: a vertex
// whose fan folds is moved to where the smallest distance to the lines of its
// opposite edges is largest, so every fan triangle is as far from inverted as it
// can be. Departure: the fan is flattened onto the plane through `apex` normal to
// `normal` (the input's orientation there), not solved on the surface; the caller
// projects the point back and checks it on the input.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh {

// `opposite` holds, for each fan triangle (apex, a, b) in its orientation, the
// pair (a, b). Returns the 3-D point of the plane that maximises the smallest
// signed distance to the directed lines a->b (positive: on their left seen along
// `normal`), or nothing for a degenerate fan (a zero normal, fewer than three
// usable edges, or no three of them meeting). For an open fan, whose optimum
// may be unbounded, the best vertex of the programme is returned; the
// untangler uses closed fans only.
std::optional<Vec3> FanKernelCenter(const Vec3& apex, const Vec3& normal,
                                    const std::vector<std::pair<Vec3, Vec3>>& opposite);

}  // namespace eqmesh

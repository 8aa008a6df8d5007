// Conformal "z^a" flattening of a vertex's 1-ring (MAPS, Lee et al. 1998, §3.2):
// the vertex goes to the origin and ring vertex k_m to r_m^a * exp(i a phi_m), with
// phi_m the accumulated 3D angles and a = 2*pi / (angle sum) for an interior vertex,
// pi / (angle sum) for a boundary vertex (its ring maps to a half disc whose two
// boundary neighbours land on the real axis).
//
// Departure: radii are divided by the largest radius before the power, so sharp
// cones (large a) cannot overflow; the map stays conformal up to that scale.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace eqmesh {

using Vec2 = Eigen::Vector2d;

// `ring` holds the neighbours of `center` in counter-clockwise order; `closed`
// says the ring wraps around (interior vertex). Returns false when the map is
// unusable: a degenerate ring, or a wedge whose image would open to pi or more
// (the fan triangles would flip).
bool FlattenRing(const Vec3& center, const std::vector<Vec3>& ring, bool closed,
                 std::vector<Vec2>* images);

// Twice the signed area of the 2D triangle (a, b, c): positive when counter-clockwise.
inline double Orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Barycentric coordinates of p in 2D triangle (a, b, c); false if it is degenerate.
bool Barycentric2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c, Eigen::Vector3d* bary);

}  // namespace eqmesh

// Conformal 1-ring flattening (MAPS, Lee et al. 1998); see ring_flattening.h.
#include "remesh/ring_flattening.h"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>

namespace eqmesh {
namespace {

// Angle between two vectors, 0 when either vanishes (coincident vertices add no wedge).
double AngleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

bool FlattenRing(const Vec3& center, const std::vector<Vec3>& ring, bool closed,
                 std::vector<Vec2>* images) {
  const size_t d = ring.size();
  if (d < 2 || (closed && d < 3)) return false;
  const size_t wedges = closed ? d : d - 1;
  // Per thread and reused: the simplification flattens a ring per re-costed
  // vertex, from every worker of its team.
  thread_local std::vector<double> theta;
  theta.resize(wedges);
  double total = 0.0, max_radius = 0.0;
  for (size_t m = 0; m < wedges; ++m) {
    theta[m] = AngleBetween(ring[m] - center, ring[(m + 1) % d] - center);
    total += theta[m];
  }
  for (const Vec3& p : ring) max_radius = std::max(max_radius, (p - center).norm());
  if (!(total > 1e-9) || !(max_radius > 0.0)) return false;
  const double pi = 3.14159265358979323846;
  const double a = (closed ? 2.0 * pi : pi) / total;
  // A wedge opened to pi or more makes its fan triangle flat or flipped.
  for (double t : theta) {
    if (a * t >= pi - 1e-3) return false;
  }
  images->resize(d);
  double phi = 0.0;
  for (size_t m = 0; m < d; ++m) {
    const double r = std::pow((ring[m] - center).norm() / max_radius, a);
    (*images)[m] = Vec2(r * std::cos(a * phi), r * std::sin(a * phi));
    if (m < wedges) phi += theta[m];
  }
  return true;
}

bool Barycentric2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c, Eigen::Vector3d* bary) {
  const double area = Orient2d(a, b, c);
  if (!(std::abs(area) > 1e-300)) return false;
  const double wa = Orient2d(p, b, c) / area;
  const double wb = Orient2d(a, p, c) / area;
  *bary = Eigen::Vector3d(wa, wb, 1.0 - wa - wb);
  return true;
}

}  // namespace eqmesh

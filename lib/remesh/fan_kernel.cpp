// Fan kernel centre: a three-variable linear programme (x, y, t) solved by
// enumerating its vertices (fans have a handful of edges); see fan_kernel.h.
#include "remesh/fan_kernel.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace eqmesh {
namespace {

// Directed line in plane coordinates: unit normal n (pointing left of a->b)
// and offset c, signed distance of x = n.x - c.
struct HalfPlane {
  Eigen::Vector2d n;
  double c;
};

std::vector<HalfPlane> FlattenFan(const Vec3& apex, const Vec3& e1, const Vec3& e2,
                                  const std::vector<std::pair<Vec3, Vec3>>& opposite) {
  std::vector<HalfPlane> planes;
  for (const auto& [a3, b3] : opposite) {
    const Eigen::Vector2d a((a3 - apex).dot(e1), (a3 - apex).dot(e2));
    const Eigen::Vector2d b((b3 - apex).dot(e1), (b3 - apex).dot(e2));
    const Eigen::Vector2d d = b - a;
    const double len = d.norm();
    if (!(len > 0.0)) continue;
    const Eigen::Vector2d n(-d.y() / len, d.x() / len);
    planes.push_back({n, n.dot(a)});
  }
  return planes;
}

double SmallestDistance(const std::vector<HalfPlane>& planes, const Eigen::Vector2d& x) {
  double t = std::numeric_limits<double>::infinity();
  for (const HalfPlane& h : planes) t = std::min(t, h.n.dot(x) - h.c);
  return t;
}

}  // namespace

std::optional<Vec3> FanKernelCenter(const Vec3& apex, const Vec3& normal,
                                    const std::vector<std::pair<Vec3, Vec3>>& opposite) {
  const double nn = normal.norm();
  if (!(nn > 0.0)) return std::nullopt;
  const Vec3 n = normal / nn;
  const Vec3 e1 = n.unitOrthogonal();
  const Vec3 e2 = n.cross(e1);
  const std::vector<HalfPlane> planes = FlattenFan(apex, e1, e2, opposite);
  if (planes.size() < 3) return std::nullopt;
  // The optimum is a vertex of the LP: three lines at equal distance t.
  double best_t = -std::numeric_limits<double>::infinity();
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  bool found = false;
  for (size_t i = 0; i < planes.size(); ++i) {
    for (size_t j = i + 1; j < planes.size(); ++j) {
      for (size_t k = j + 1; k < planes.size(); ++k) {
        Eigen::Matrix3d m;
        Eigen::Vector3d rhs;
        for (int r = 0; r < 3; ++r) {
          const HalfPlane& h = planes[r == 0 ? i : r == 1 ? j : k];
          m.row(r) << h.n.x(), h.n.y(), -1.0;
          rhs(r) = h.c;
        }
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
        if (!lu.isInvertible()) continue;
        const Eigen::Vector3d s = lu.solve(rhs);
        const Eigen::Vector2d x = s.head<2>();
        const double t = SmallestDistance(planes, x);
        if (std::isfinite(t) && t > best_t) {
          best_t = t;
          best = x;
          found = true;
        }
      }
    }
  }
  if (!found) return std::nullopt;
  return Vec3(apex + best.x() * e1 + best.y() * e2);
}

}  // namespace eqmesh

#include "hard_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "test_support.h"

namespace eqmesh::testing {
namespace {

// A closed surface of revolution around z through the profile points
// (radius, z), the first and last of radius 0 (the poles), `around` vertices per ring.
Mesh Revolve(const std::vector<std::pair<double, double>>& profile, int around) {
  Mesh mesh;
  const uint32_t south = 0;
  mesh.positions.emplace_back(0.0, 0.0, profile.front().second);
  const int rings = static_cast<int>(profile.size()) - 2;
  for (int r = 0; r < rings; ++r) {
    const auto [radius, z] = profile[static_cast<size_t>(r) + 1];
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      mesh.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  }
  const uint32_t north = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(0.0, 0.0, profile.back().second);
  auto at = [&](int r, int i) { return static_cast<uint32_t>(1 + r * around + (i % around)); };
  for (int i = 0; i < around; ++i) {
    mesh.faces.push_back({south, at(0, i + 1), at(0, i)});
    mesh.faces.push_back({north, at(rings - 1, i), at(rings - 1, i + 1)});
    for (int r = 0; r + 1 < rings; ++r) {
      mesh.faces.push_back({at(r, i), at(r, i + 1), at(r + 1, i + 1)});
      mesh.faces.push_back({at(r, i), at(r + 1, i + 1), at(r + 1, i)});
    }
  }
  return mesh;
}

// `count` points evenly spaced by arc length along the curve z -> (r(z), z), z in [z0, z1].
template <typename Radius>
std::vector<std::pair<double, double>> EvenProfile(Radius radius, double z0, double z1, int count) {
  const int fine = 20000;
  std::vector<std::pair<double, double>> curve;
  std::vector<double> length{0.0};
  for (int k = 0; k <= fine; ++k) {
    const double z = z0 + (z1 - z0) * k / fine;
    curve.emplace_back(radius(z), z);
    if (k > 0) {
      length.push_back(length.back() + std::hypot(curve[k].first - curve[k - 1].first, curve[k].second - curve[k - 1].second));
    }
  }
  std::vector<std::pair<double, double>> out;
  size_t j = 0;
  for (int k = 0; k < count; ++k) {
    const double s = length.back() * k / (count - 1);
    while (j + 1 < length.size() && length[j + 1] < s) ++j;
    out.push_back(curve[std::min(j + (k > 0 ? 1 : 0), curve.size() - 1)]);
  }
  out.front().first = 0.0;
  out.back().first = 0.0;
  return out;
}

}  // namespace

Mesh MakeDumbbell(double neck) {
  auto radius = [neck](double z) {
    const double a = 1.0 - (z + 2.0) * (z + 2.0), b = 1.0 - (z - 2.0) * (z - 2.0);
    const double spheres = std::max(a > 0.0 ? std::sqrt(a) : 0.0, b > 0.0 ? std::sqrt(b) : 0.0);
    return std::abs(z) < 2.0 ? std::max(neck, spheres) : spheres;
  };
  return Revolve(EvenProfile(radius, -3.0, 3.0, 90), 48);
}

Mesh MakeSpikyStar(double length) {
  Mesh mesh = MakeIcosphere(4);
  const std::array<Vec3, 6> axes = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                    Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  for (Vec3& p : mesh.positions) {
    const Vec3 n = p.normalized();
    double pull = 0.0;
    for (const Vec3& a : axes) pull = std::max(pull, std::pow(std::max(0.0, n.dot(a)), 60.0));
    p = (1.0 + length * pull) * n;
  }
  return mesh;
}

Mesh MakePretzel() {
  // A 39 x 15 x 3 voxel plate with three 6 x 5 holes through it.
  const int nx = 39, ny = 15, nz = 3;
  auto filled = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return false;
    const bool hole_y = j >= 5 && j < 10;
    const bool hole_x = (i >= 6 && i < 12) || (i >= 17 && i < 23) || (i >= 28 && i < 34);
    return !(hole_x && hole_y);
  };
  Mesh mesh;
  std::map<std::array<int, 3>, uint32_t> index;
  auto vertex = [&](std::array<int, 3> c) {
    const auto [it, added] = index.emplace(c, static_cast<uint32_t>(mesh.positions.size()));
    if (added) mesh.positions.emplace_back(c[0], c[1], c[2]);
    return it->second;
  };
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      for (int k = 0; k < nz; ++k) {
        if (!filled(i, j, k)) continue;
        const std::array<int, 3> cell = {i, j, k};
        for (int axis = 0; axis < 3; ++axis) {
          for (int side : {-1, 1}) {
            std::array<int, 3> next = cell;
            next[static_cast<size_t>(axis)] += side;
            if (filled(next[0], next[1], next[2])) continue;
            // Corners p, p+e_b, p+e_b+e_c, p+e_c with e_b x e_c = e_axis: CCW seen from +axis.
            const size_t a = static_cast<size_t>(axis), b = (a + 1) % 3, c = (a + 2) % 3;
            std::array<int, 3> p = cell;
            if (side > 0) p[a] += 1;
            std::array<int, 3> pb = p, pc = p, pbc = p;
            pb[b] += 1;
            pc[c] += 1;
            pbc[b] += 1;
            pbc[c] += 1;
            std::array<uint32_t, 4> q = {vertex(p), vertex(pb), vertex(pbc), vertex(pc)};
            if (side < 0) std::swap(q[1], q[3]);
            mesh.faces.push_back({q[0], q[1], q[2]});
            mesh.faces.push_back({q[0], q[2], q[3]});
          }
        }
      }
    }
  }
  // Laplacian steps round the voxel creases (the topology stays).
  std::vector<std::set<uint32_t>> ring(mesh.positions.size());
  for (const Face& f : mesh.faces) {
    for (int c = 0; c < 3; ++c) {
      ring[f[c]].insert(f[(c + 1) % 3]);
      ring[f[c]].insert(f[(c + 2) % 3]);
    }
  }
  for (int step = 0; step < 12; ++step) {
    std::vector<Vec3> next = mesh.positions;
    for (size_t v = 0; v < next.size(); ++v) {
      Vec3 centre = Vec3::Zero();
      for (uint32_t w : ring[v]) centre += mesh.positions[w];
      centre /= static_cast<double>(ring[v].size());
      next[v] = 0.5 * (mesh.positions[v] + centre);
    }
    mesh.positions = std::move(next);
  }
  return mesh;
}

int ClosedGenus(const Mesh& mesh) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const Face& f : mesh.faces) {
    for (int c = 0; c < 3; ++c) edges.insert(std::minmax(f[c], f[(c + 1) % 3]));
  }
  const long euler = static_cast<long>(mesh.positions.size()) - static_cast<long>(edges.size()) +
                     static_cast<long>(mesh.faces.size());
  return static_cast<int>((2 - euler) / 2);
}

Mesh MakeGridBox(double sx, double sy, double sz, int cells_per_unit) {
  Mesh mesh;
  std::map<std::array<long long, 3>, uint32_t> index;
  const auto vertex = [&](const Vec3& p) {
    const std::array<long long, 3> key{std::llround(p.x() * 1e9), std::llround(p.y() * 1e9), std::llround(p.z() * 1e9)};
    const auto [it, added] = index.emplace(key, static_cast<uint32_t>(mesh.positions.size()));
    if (added) mesh.positions.push_back(p);
    return it->second;
  };
  // Each side: an origin and two edge vectors ordered so a x b points outward.
  const Vec3 o(0, 0, 0), x(sx, 0, 0), y(0, sy, 0), z(0, 0, sz);
  const std::array<std::array<Vec3, 3>, 6> sides{{{o, y, x}, {z, x, y}, {o, z, y}, {x, y, z}, {o, x, z}, {y, z, x}}};
  for (const std::array<Vec3, 3>& side : sides) {
    // Named copies, not structured bindings: C++17 lambdas cannot capture those.
    const Vec3 origin = side[0], a = side[1], b = side[2];
    const int na = std::max(1, static_cast<int>(std::lround(a.norm() * cells_per_unit)));
    const int nb = std::max(1, static_cast<int>(std::lround(b.norm() * cells_per_unit)));
    const auto at = [&](int i, int j) { return vertex(origin + a * (double(i) / na) + b * (double(j) / nb)); };
    for (int j = 0; j < nb; ++j) {
      for (int i = 0; i < na; ++i) {
        const uint32_t p = at(i, j), q = at(i + 1, j), r = at(i, j + 1), s = at(i + 1, j + 1);
        mesh.faces.push_back({p, q, s});
        mesh.faces.push_back({p, s, r});
      }
    }
  }
  return mesh;
}

}  // namespace eqmesh::testing

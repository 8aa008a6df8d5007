#include "test_support.h"

#include <cmath>
#include <sys/stat.h>

#include "mesh/semi_regular.h"

namespace eqmesh::testing {

std::string SharedPath(const std::string& relative) {
  return std::string(EQMESH_SHARED_DIR) + "/" + relative;
}

bool HaveSharedMeshes() {
  struct stat st {};
  return stat(SharedPath("meshes/MANIFEST.md").c_str(), &st) == 0;
}

Mesh MakeIcosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},   {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::vector<Face> fine;
    std::vector<Edge> odd;
    SubdivideConnectivity(static_cast<uint32_t>(m.positions.size()), m.faces, &fine, &odd);
    for (const Edge& e : odd) m.positions.push_back(0.5 * (m.positions[e[0]] + m.positions[e[1]]));
    m.faces = std::move(fine);
  }
  for (Vec3& p : m.positions) p = radius * p.normalized();
  return m;
}

Mesh MakeTorus(int n, int m, double major_radius, double minor_radius) {
  Mesh mesh;
  const double two_pi = 2.0 * M_PI;
  for (int i = 0; i < n; ++i) {
    const double u = two_pi * i / n;
    for (int j = 0; j < m; ++j) {
      const double v = two_pi * j / m;
      const double r = major_radius + minor_radius * std::cos(v);
      mesh.positions.emplace_back(r * std::cos(u), r * std::sin(u), minor_radius * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<uint32_t>(((i + n) % n) * m + ((j + m) % m)); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

CubeWithEdges MakeCube() {
  CubeWithEdges c;
  for (int i = 0; i < 8; ++i) c.mesh.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Each side (a, b, c, d) counter-clockwise from outside: triangles (a, b, c), (a, c, d).
  const uint32_t sides[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& s : sides) {
    c.mesh.faces.push_back({s[0], s[1], s[2]});
    c.mesh.faces.push_back({s[0], s[2], s[3]});
    for (int i = 0; i < 4; ++i) c.edges.push_back({s[i], s[(i + 1) % 4]});
  }
  return c;
}

Mesh MakeCappedCylinder(double r, double h, int around, int rings) {
  Mesh mesh;
  for (int k = 0; k < rings; ++k) {
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      mesh.positions.emplace_back(r * std::cos(a), r * std::sin(a), h * k / (rings - 1));
    }
  }
  const uint32_t bottom = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(0.0, 0.0, 0.0);
  mesh.positions.emplace_back(0.0, 0.0, h);
  const auto at = [&](int k, int i) { return static_cast<uint32_t>(k * around + (i % around)); };
  for (int i = 0; i < around; ++i) {
    mesh.faces.push_back({bottom, at(0, i + 1), at(0, i)});
    mesh.faces.push_back({bottom + 1, at(rings - 1, i), at(rings - 1, i + 1)});
    for (int k = 0; k + 1 < rings; ++k) {
      mesh.faces.push_back({at(k, i), at(k, i + 1), at(k + 1, i + 1)});
      mesh.faces.push_back({at(k, i), at(k + 1, i + 1), at(k + 1, i)});
    }
  }
  return mesh;
}

Mesh MakeDisc(int rings, double radius) {
  Mesh mesh;
  mesh.positions.emplace_back(0, 0, 0);
  // Ring k has 6k vertices: a hexagonal disc whose interior vertices have valence 6.
  std::vector<uint32_t> ring_start(rings + 1, 0);
  for (int k = 1; k <= rings; ++k) {
    ring_start[k] = static_cast<uint32_t>(mesh.positions.size());
    for (int i = 0; i < 6 * k; ++i) {
      const double a = 2.0 * M_PI * i / (6 * k);
      const double r = radius * k / rings;
      mesh.positions.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    }
  }
  auto at = [&](int k, int i) {
    if (k == 0) return 0u;
    return ring_start[k] + static_cast<uint32_t>(((i % (6 * k)) + 6 * k) % (6 * k));
  };
  for (int k = 1; k <= rings; ++k) {
    // Walk the outer ring; each outer vertex i maps to inner position i*(k-1)/k.
    for (int side = 0; side < 6; ++side) {
      for (int s = 0; s < k; ++s) {
        const int outer = side * k + s;
        const int inner = side * (k - 1) + s;
        mesh.faces.push_back({at(k - 1, inner), at(k, outer), at(k, outer + 1)});
        if (s < k - 1) mesh.faces.push_back({at(k - 1, inner), at(k, outer + 1), at(k - 1, inner + 1)});
      }
    }
  }
  return mesh;
}

Mesh MakeTriangleSoup(const Mesh& mesh) {
  Mesh soup;
  for (const Face& f : mesh.faces) {
    const uint32_t first = static_cast<uint32_t>(soup.positions.size());
    for (uint32_t v : f) soup.positions.push_back(mesh.positions[v]);
    soup.faces.push_back({first, first + 1, first + 2});
  }
  return soup;
}

Mesh WithComponent(Mesh a, const Mesh& b, const Vec3& shift) {
  const uint32_t offset = static_cast<uint32_t>(a.positions.size());
  for (const Vec3& p : b.positions) a.positions.push_back(p + shift);
  for (const Face& f : b.faces) a.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return a;
}

double LargestExtent(const Mesh& mesh) {
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).maxCoeff();
}

}  // namespace eqmesh::testing

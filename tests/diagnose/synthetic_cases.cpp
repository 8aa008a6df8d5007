#include "diagnose/synthetic_cases.h"

#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "test_support.h"

namespace eqmesh::testing {

Mesh MakeTriangle() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}};
  return m;
}

Mesh MakeBowtie() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  return m;
}

Mesh MakeTetrahedron(const Vec3& offset) {
  Mesh m;
  m.positions = {offset + Vec3(0, 0, 0), offset + Vec3(1, 0, 0), offset + Vec3(0, 1, 0),
                 offset + Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

Mesh MakeTetrahedraSharingVertex() {
  // Second tetrahedron mirrored through the origin, glued at vertex 0.
  Mesh a = MakeTetrahedron();
  Mesh m = a;
  for (int i = 1; i < 4; ++i) m.positions.push_back(-a.positions[i]);
  auto id = [](uint32_t v) { return v == 0 ? 0u : v + 3u; };
  for (const Face& f : a.faces) m.faces.push_back({id(f[0]), id(f[2]), id(f[1])});  // mirror flips
  return m;
}

Mesh MakeThreeFacesOnEdge() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  return m;
}

Mesh MakeSphereWithFlippedFace(int face) {
  Mesh m = MakeIcosphere(1);
  std::swap(m.faces[face][1], m.faces[face][2]);
  return m;
}

Mesh MakeMobiusStrip(int n) {
  Mesh m;
  for (int i = 0; i < n; ++i) {
    const double u = 2.0 * M_PI * i / n;
    for (int s = -1; s <= 1; s += 2) {
      const double w = 0.3 * s;
      m.positions.emplace_back((1 + w * std::cos(u / 2)) * std::cos(u), (1 + w * std::cos(u / 2)) * std::sin(u),
                               w * std::sin(u / 2));
    }
  }
  for (int i = 0; i < n; ++i) {
    const uint32_t a = static_cast<uint32_t>(2 * i), b = a + 1;
    // The last quad joins the first one with its sides swapped: the half twist.
    const bool last = i == n - 1;
    const uint32_t c = last ? 1u : a + 2, d = last ? 0u : a + 3;
    m.faces.push_back({a, c, b});
    m.faces.push_back({b, c, d});
  }
  return m;
}

Mesh MakeSplitSphere() {
  Mesh m = MakeIcosphere(2);
  const uint32_t n = static_cast<uint32_t>(m.positions.size());
  for (uint32_t v = 0; v < n; ++v) m.positions.push_back(m.positions[v]);
  for (Face& f : m.faces) {
    const double z = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]).z();
    if (z < 0)
      for (uint32_t& v : f) v += n;
  }
  return m;
}

Mesh Concatenate(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const uint32_t shift = static_cast<uint32_t>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (const Face& f : b.faces) m.faces.push_back({f[0] + shift, f[1] + shift, f[2] + shift});
  return m;
}

double SignedVolume(const Mesh& mesh) {
  double six_v = 0.0;
  for (const Face& f : mesh.faces)
    six_v += mesh.positions[f[0]].dot(mesh.positions[f[1]].cross(mesh.positions[f[2]]));
  return six_v / 6.0;
}

}  // namespace eqmesh::testing

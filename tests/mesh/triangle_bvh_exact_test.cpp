// TriangleBvh closest-point answers are part of the remesher's output, so they
// must not change by a bit when the tree's memory layout or arithmetic is
// reworked: same face among equal-distance ties, same point, barycentrics and
// squared distance. The mesh and queries here use only exact arithmetic on
// raw generator bits (no libm), so the golden hash holds on every target.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "mesh/triangle_bvh.h"

namespace eqmesh {
namespace {

class ExactRng {
 public:
  explicit ExactRng(uint64_t seed) : engine_(seed) {}
  // Multiple of 2^-20 in [lo, hi): coordinates that repeat exactly, so shared
  // edges and vertices produce genuine distance ties.
  double Grid(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine_() >> 44) * 0x1.0p-20;
  }

 private:
  std::mt19937_64 engine_;
};

// Bumpy height field over [0, n]^2 (two triangles per cell) plus degenerate
// faces: collinear, coincident corners and a sliver below the 1e-8 rad angle
// threshold, all of which take ClosestPointOnTriangle's edge-only path.
Mesh MakeTestSurface(int n) {
  ExactRng rng(5);
  Mesh mesh;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) mesh.positions.push_back({double(x), double(y), rng.Grid(0, 2)});
  const auto id = [n](int x, int y) { return static_cast<uint32_t>(y * (n + 1) + x); };
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      mesh.faces.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      mesh.faces.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  const auto add = [&mesh](const Vec3& a, const Vec3& b, const Vec3& c) {
    const auto v = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.faces.push_back({v, v + 1, v + 2});
  };
  add({2, 2, 3}, {4, 2, 3}, {3, 2, 3});              // collinear
  add({5, 5, -1}, {5, 5, -1}, {5, 5, -1});           // one point
  add({1, 6, 2.5}, {7, 6, 2.5}, {4, 6 + 1e-12, 2.5});  // sliver
  return mesh;
}

uint64_t Bits(double d) {
  uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return u;
}

void HashIn(uint64_t* h, uint64_t v) {
  for (int i = 0; i < 8; ++i) {
    *h ^= (v >> (8 * i)) & 0xff;
    *h *= 0x100000001b3ull;  // FNV-1a
  }
}

uint64_t HashResult(uint64_t h, const ClosestPointResult& r) {
  HashIn(&h, r.face);
  for (int k = 0; k < 3; ++k) HashIn(&h, Bits(r.point[k]));
  for (double b : r.barycentric) HashIn(&h, Bits(b));
  HashIn(&h, Bits(r.squared_distance));
  return h;
}

// Queries on vertices, edge midpoints and just off the surface (where ties
// between faces sharing an edge or vertex are common), and far away.
std::vector<Vec3> MakeQueries(const Mesh& mesh) {
  ExactRng rng(9);
  std::vector<Vec3> queries;
  for (size_t f = 0; f < mesh.faces.size(); f += 3) {
    const Vec3& a = mesh.positions[mesh.faces[f][0]];
    const Vec3& b = mesh.positions[mesh.faces[f][1]];
    queries.push_back(a);
    queries.push_back(0.5 * (a + b));
    queries.push_back(a + Vec3(rng.Grid(-0.5, 0.5), rng.Grid(-0.5, 0.5), rng.Grid(-1, 1)));
  }
  for (int i = 0; i < 200; ++i)
    queries.push_back({rng.Grid(-20, 40), rng.Grid(-20, 40), rng.Grid(-20, 20)});
  return queries;
}

TEST(TriangleBvhExact, ResultsAreExactlyTheTriangleRoutinesOnTheNearestFace) {
  const Mesh mesh = MakeTestSurface(16);
  auto bvh = TriangleBvh::Build(mesh);
  ASSERT_TRUE(bvh.ok()) << bvh.status().ToString();
  for (const Vec3& p : MakeQueries(mesh)) {
    const ClosestPointResult r = bvh->ClosestPoint(p);
    ASSERT_TRUE(r.found());
    double brute = std::numeric_limits<double>::infinity();
    for (const Face& f : mesh.faces) {
      std::array<double, 3> bary;
      const Vec3 q = ClosestPointOnTriangle(p, mesh.positions[f[0]], mesh.positions[f[1]],
                                            mesh.positions[f[2]], &bary);
      brute = std::min(brute, (q - p).squaredNorm());
    }
    EXPECT_EQ(Bits(r.squared_distance), Bits(brute));
    const Face& f = mesh.faces[r.face];
    std::array<double, 3> bary;
    const Vec3 q = ClosestPointOnTriangle(p, mesh.positions[f[0]], mesh.positions[f[1]],
                                          mesh.positions[f[2]], &bary);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(Bits(r.point[k]), Bits(q[k]));
      EXPECT_EQ(Bits(r.barycentric[k]), Bits(bary[k]));
    }
  }
}

TEST(TriangleBvhExact, AnswersMatchGoldenHash) {
  const Mesh mesh = MakeTestSurface(16);
  auto bvh = TriangleBvh::Build(mesh);
  ASSERT_TRUE(bvh.ok()) << bvh.status().ToString();
  uint64_t h = 0xcbf29ce484222325ull;
  for (const Vec3& p : MakeQueries(mesh)) {
    h = HashResult(h, bvh->ClosestPoint(p));
    h = HashResult(h, bvh->ClosestPoint(p, 0.25));
    h = HashResult(h, bvh->ClosestPointFiltered(p, [](uint32_t f) { return f % 3 != 0; }));
  }
  // Recorded from the layout before the NodePair repacking; a change here
  // means some query now picks another face, point or rounding.
  EXPECT_EQ(h, 0xe13673457ab6e89bull);
}

}  // namespace
}  // namespace eqmesh

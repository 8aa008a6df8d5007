#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "mesh/triangle_bvh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// Raw 64-bit outputs of mt19937_64 are specified by the standard, so this is
// reproducible everywhere (unlike std:: distributions).
class TestRng {
 public:
  explicit TestRng(uint64_t seed) : engine_(seed) {}
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }
  Vec3 InBox(double half) { return {Uniform(-half, half), Uniform(-half, half), Uniform(-half, half)}; }

 private:
  std::mt19937_64 engine_;
};

double BruteForceDistance2(const Mesh& m, const Vec3& p, uint32_t* face = nullptr,
                           const std::function<bool(uint32_t)>& filter = nullptr) {
  double best = std::numeric_limits<double>::infinity();
  for (uint32_t f = 0; f < m.faces.size(); ++f) {
    if (filter && !filter(f)) continue;
    std::array<double, 3> bary;
    const Vec3 q = ClosestPointOnTriangle(p, m.positions[m.faces[f][0]], m.positions[m.faces[f][1]],
                                          m.positions[m.faces[f][2]], &bary);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best) {
      best = d2;
      if (face) *face = f;
    }
  }
  return best;
}

// Plain Möller–Trumbore without epsilons: the reference for rays in general position.
std::vector<double> BruteForceRayTs(const Mesh& m, const Vec3& o, const Vec3& d, double tmin,
                                    double tmax) {
  std::vector<double> ts;
  for (const Face& f : m.faces) {
    const Vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    const Vec3 e1 = b - a, e2 = c - a, pv = d.cross(e2);
    const double det = e1.dot(pv);
    if (det == 0.0) continue;
    const Vec3 tv = o - a, qv = tv.cross(e1);
    const double u = tv.dot(pv) / det, v = d.dot(qv) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double t = e2.dot(qv) / det;
    if (t >= tmin && t <= tmax) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

TEST(ClosestPointOnTriangle, RegionsAndBarycentrics) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  std::array<double, 3> bary;
  EXPECT_TRUE(ClosestPointOnTriangle({0.25, 0.25, 3}, a, b, c, &bary).isApprox(Vec3(0.25, 0.25, 0)));
  EXPECT_NEAR(bary[0], 0.5, 1e-15);
  EXPECT_NEAR(bary[1], 0.25, 1e-15);
  EXPECT_TRUE(ClosestPointOnTriangle({-1, -1, 0}, a, b, c, &bary).isApprox(a));
  EXPECT_EQ(bary[0], 1.0);
  EXPECT_TRUE(ClosestPointOnTriangle({2, 2, 0}, a, b, c, &bary).isApprox(Vec3(0.5, 0.5, 0)));
  EXPECT_NEAR(bary[1], 0.5, 1e-15);
  EXPECT_TRUE(ClosestPointOnTriangle({0.5, -2, 1}, a, b, c, &bary).isApprox(Vec3(0.5, 0, 0)));
}

TEST(ClosestPointOnTriangle, DegenerateTrianglesGiveFiniteSegmentAnswers) {
  std::array<double, 3> bary;
  // Collinear corners: the closest point is on the segment [0, 2] of the x axis.
  Vec3 q = ClosestPointOnTriangle({1, 1, 0}, {0, 0, 0}, {2, 0, 0}, {1, 0, 0}, &bary);
  EXPECT_TRUE(q.allFinite());
  EXPECT_NEAR((q - Vec3(1, 0, 0)).norm(), 0.0, 1e-15);
  // All corners coincide.
  q = ClosestPointOnTriangle({1, 1, 1}, {3, 3, 3}, {3, 3, 3}, {3, 3, 3}, &bary);
  EXPECT_EQ(q, Vec3(3, 3, 3));
  EXPECT_NEAR(bary[0] + bary[1] + bary[2], 1.0, 1e-15);
  // Two corners coincide.
  q = ClosestPointOnTriangle({5, 1, 0}, {0, 0, 0}, {0, 0, 0}, {4, 0, 0}, &bary);
  EXPECT_EQ(q, Vec3(4, 0, 0));
}

TEST(TriangleBvh, ClosestPointMatchesBruteForce) {
  Mesh mesh = testing::MakeTorus(24, 12);
  // Add degenerate faces: they must not break the search.
  mesh.faces.push_back({0, 0, 0});
  mesh.faces.push_back({0, 1, 2});
  mesh.positions[2] = 0.5 * (mesh.positions[0] + mesh.positions[1]);
  auto bvh = TriangleBvh::Build(mesh);
  ASSERT_TRUE(bvh.ok()) << bvh.status().ToString();
  TestRng rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = rng.InBox(i % 2 ? 1.6 : 5.0);
    const ClosestPointResult r = bvh->ClosestPoint(p);
    ASSERT_TRUE(r.found());
    const double expected = BruteForceDistance2(mesh, p);
    EXPECT_NEAR(r.squared_distance, expected, 1e-12 * (1 + expected));
    EXPECT_NEAR((r.point - p).squaredNorm(), r.squared_distance, 1e-12);
    const Face& f = mesh.faces[r.face];
    const Vec3 from_bary = r.barycentric[0] * mesh.positions[f[0]] +
                           r.barycentric[1] * mesh.positions[f[1]] +
                           r.barycentric[2] * mesh.positions[f[2]];
    EXPECT_LT((from_bary - r.point).norm(), 1e-9);
  }
}

TEST(TriangleBvh, FilteredAndBoundedQueries) {
  const Mesh mesh = testing::MakeIcosphere(3);
  auto bvh = TriangleBvh::Build(mesh);
  ASSERT_TRUE(bvh.ok());
  auto even = [](uint32_t f) { return f % 7 == 3; };
  TestRng rng(11);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p = rng.InBox(2.0);
    const ClosestPointResult r = bvh->ClosestPointFiltered(p, even);
    ASSERT_TRUE(r.found());
    EXPECT_TRUE(even(r.face));
    EXPECT_NEAR(r.squared_distance, BruteForceDistance2(mesh, p, nullptr, even), 1e-12);
  }
  // Nothing within max_dist: not found; exactly at max_dist: found.
  EXPECT_FALSE(bvh->ClosestPoint({0, 0, 5}, 3.5).found());
  EXPECT_TRUE(bvh->ClosestPoint({0, 0, 5}, 4.0 + 1e-12).found());
  EXPECT_FALSE(bvh->ClosestPointFiltered({0, 0, 0}, [](uint32_t) { return false; }).found());
  EXPECT_FALSE(bvh->ClosestPoint({NAN, 0, 0}).found());
}

// A tree refitted to moved corners answers as one built from them: the same
// distances for closest points and rays (here the corners are shrunk towards the
// centre, so every box moves), and a refit to the positions it was built from
// changes nothing. A mesh with other faces is refused.
TEST(TriangleBvh, RefittedTreeAnswersAsABuiltOne) {
  const Mesh mesh = testing::MakeTorus(24, 12);
  Mesh moved = mesh;
  TestRng jitter(5);
  for (Vec3& p : moved.positions) p = 0.7 * p + jitter.InBox(0.02);
  auto built = TriangleBvh::Build(moved);
  auto refitted = TriangleBvh::Build(mesh);
  ASSERT_TRUE(built.ok() && refitted.ok());
  ASSERT_TRUE(refitted->Refit(moved).ok());
  EXPECT_EQ(refitted->bounds().min, built->bounds().min);
  EXPECT_EQ(refitted->bounds().max, built->bounds().max);
  TestRng rng(9);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = rng.InBox(i % 2 ? 1.2 : 4.0);
    const ClosestPointResult a = refitted->ClosestPoint(p);
    const ClosestPointResult b = built->ClosestPoint(p);
    ASSERT_TRUE(a.found() && b.found());
    EXPECT_EQ(a.squared_distance, b.squared_distance);
    EXPECT_EQ(a.squared_distance, BruteForceDistance2(moved, p));
    const Vec3 d = rng.InBox(1.0).normalized();
    std::vector<RayHit> ha, hb;
    refitted->RayAllHits(p, d, 0.0, 10.0, &ha);
    built->RayAllHits(p, d, 0.0, 10.0, &hb);
    ASSERT_EQ(ha.size(), hb.size());
    for (size_t k = 0; k < ha.size(); ++k) EXPECT_EQ(ha[k].t, hb[k].t);
  }
  auto again = TriangleBvh::Build(mesh);
  ASSERT_TRUE(again.ok() && again->Refit(mesh).ok());
  for (int i = 0; i < 200; ++i) {
    const Vec3 p = rng.InBox(2.0);
    EXPECT_EQ(again->ClosestPoint(p).squared_distance, BruteForceDistance2(mesh, p));
  }
  Mesh fewer = mesh;
  fewer.faces.pop_back();
  EXPECT_FALSE(refitted->Refit(fewer).ok());
  Mesh broken = mesh;
  broken.positions[0].x() = NAN;
  EXPECT_FALSE(refitted->Refit(broken).ok());
}

TEST(TriangleBvh, RayAllHitsMatchesBruteForce) {
  const Mesh mesh = testing::MakeTorus(20, 10);
  auto bvh = TriangleBvh::Build(mesh);
  ASSERT_TRUE(bvh.ok());
  TestRng rng(3);
  std::vector<RayHit> hits;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o = rng.InBox(2.0);
    const Vec3 d = rng.InBox(1.0);
    bvh->RayAllHits(o, d, -10.0, 10.0, &hits);
    const std::vector<double> expected = BruteForceRayTs(mesh, o, d, -10.0, 10.0);
    ASSERT_EQ(hits.size(), expected.size()) << "ray " << i;
    for (size_t k = 0; k < hits.size(); ++k) {
      EXPECT_NEAR(hits[k].t, expected[k], 1e-9);
      if (k > 0) {
        EXPECT_LE(hits[k - 1].t, hits[k].t);
      }
    }
    auto first = bvh->RayFirstHit(o, d, 0.0, 10.0);
    const auto pos = std::lower_bound(expected.begin(), expected.end(), 0.0);
    ASSERT_EQ(first.has_value(), pos != expected.end());
    if (first) {
      EXPECT_NEAR(first->t, *pos, 1e-9);
    }
  }
}

TEST(TriangleBvh, RaysThroughSharedEdgesAndVerticesHitOnce) {
  // Ray through every vertex of a closed sphere from its centre: exactly one
  // crossing, even though it lands on a vertex shared by 5 or 6 faces.
  const Mesh sphere = testing::MakeIcosphere(2);
  auto bvh = TriangleBvh::Build(sphere);
  ASSERT_TRUE(bvh.ok());
  std::vector<RayHit> hits;
  for (const Vec3& v : sphere.positions) {
    bvh->RayAllHits(Vec3::Zero(), v, 0.0, 2.0, &hits);
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_NEAR(hits[0].t, 1.0, 1e-12);
  }
  // Rays through edge midpoints (shared by two faces) and through the
  // whole sphere (two crossings).
  for (const Face& f : sphere.faces) {
    const Vec3 mid = 0.5 * (sphere.positions[f[0]] + sphere.positions[f[1]]);
    bvh->RayAllHits(-2.0 * mid, mid, 0.0, 5.0, &hits);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_NEAR(hits[0].t, 1.0, 1e-12);
    EXPECT_NEAR(hits[1].t, 3.0, 1e-12);
    EXPECT_TRUE(bvh->RayFirstHit(Vec3::Zero(), mid, 0.0, 5.0).has_value());
  }
  // Flat disc, ray along z through each interior vertex: one hit.
  const Mesh disc = testing::MakeDisc(4);
  auto dbvh = TriangleBvh::Build(disc);
  ASSERT_TRUE(dbvh.ok());
  for (const Vec3& v : disc.positions) {
    dbvh->RayAllHits(v + Vec3(0, 0, 1), Vec3(0, 0, -1), 0.0, 2.0, &hits);
    ASSERT_EQ(hits.size(), 1u);
  }
}

TEST(TriangleBvh, RejectsBadMeshes) {
  Mesh empty;
  EXPECT_EQ(TriangleBvh::Build(empty).status().code(), StatusCode::kInvalidMesh);
  Mesh bad_index = testing::MakeIcosphere(0);
  bad_index.faces[3][1] = 99;
  EXPECT_EQ(TriangleBvh::Build(bad_index).status().code(), StatusCode::kInvalidMesh);
  Mesh nan = testing::MakeIcosphere(0);
  nan.positions[4].y() = NAN;
  EXPECT_EQ(TriangleBvh::Build(nan).status().code(), StatusCode::kInvalidMesh);
  // All faces at one point: builds (median fallback), answers queries.
  Mesh point;
  point.positions.assign(3, Vec3(1, 2, 3));
  point.faces.assign(100, Face{0, 1, 2});
  auto bvh = TriangleBvh::Build(point);
  ASSERT_TRUE(bvh.ok());
  EXPECT_NEAR(bvh->ClosestPoint({1, 2, 4}).squared_distance, 1.0, 1e-15);
}

TEST(TriangleBvh, BuildsMillionTrianglesQuickly) {
  const Mesh mesh = testing::MakeIcosphere(7);  // 327,680 faces: keeps the test fast under ASan
  const auto start = std::chrono::steady_clock::now();
  auto bvh = TriangleBvh::Build(mesh);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(bvh.ok());
  EXPECT_EQ(bvh->num_faces(), mesh.faces.size());
  // Not a timing assertion (those live in bench/); printed for the record.
  std::printf("BVH build, %zu faces: %.3f s\n", mesh.faces.size(), seconds);
  EXPECT_NEAR(bvh->ClosestPoint({0, 0, 2}).squared_distance, 1.0, 1e-6);
}

}  // namespace
}  // namespace eqmesh

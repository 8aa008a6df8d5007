// The quadric simplification behind the simplified as-is representation: the
// result is a manifold, consistently oriented mesh of the same topology whose
// vertices are input vertices, flat regions simplify exactly, boundaries keep
// their vertices, the error grows with the reduction, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "mesh/diagnose.h"
#include "metrics/surface_distance.h"
#include "remesh/quadric_simplification.h"
#include "remesh/quality_checks.h"
#include "test_support.h"

namespace eqmesh {
namespace {

void ExpectCleanWithTopologyOf(const Mesh& simplified, const Mesh& input) {
  const MeshDiagnosis in = Diagnose(input), out = Diagnose(simplified);
  EXPECT_TRUE(out.IsCleanForRemeshing());
  EXPECT_EQ(out.referenced_vertices, simplified.positions.size());
  EXPECT_EQ(out.components, in.components);
  EXPECT_EQ(out.closed_genus, in.closed_genus);
  EXPECT_EQ(out.boundary_loops, in.boundary_loops);
}

// Every vertex of the result is one of the input's, at the same position, in
// the input's order.
void ExpectInputVertices(const Mesh& simplified, const Mesh& input) {
  size_t next = 0;
  for (const Vec3& p : simplified.positions) {
    while (next < input.positions.size() && input.positions[next] != p) ++next;
    ASSERT_LT(next, input.positions.size());
    ++next;
  }
}

TEST(QuadricSimplification, TorusKeepsItsTopologyAndFacesAgreeWithTheInput) {
  const Mesh torus = testing::MakeTorus(48, 24);
  for (const size_t target : {size_t{900}, size_t{400}, size_t{150}}) {
    auto simplified = SimplifyByQuadrics(torus, target);
    ASSERT_TRUE(simplified.ok()) << simplified.status().ToString();
    EXPECT_EQ(simplified->positions.size(), target);
    ExpectCleanWithTopologyOf(*simplified, torus);
    ExpectInputVertices(*simplified, torus);
    auto folds = CountFoldsAgainstInput(*simplified, torus);
    ASSERT_TRUE(folds.ok());
    EXPECT_EQ(folds->flipped_faces, 0u) << target;
  }
}

TEST(QuadricSimplification, ErrorGrowsWithTheReduction) {
  const Mesh sphere = testing::MakeIcosphere(4);  // 2,562 vertices
  double last = std::numeric_limits<double>::infinity();
  for (const size_t target : {size_t{2000}, size_t{1000}, size_t{300}}) {
    auto simplified = SimplifyByQuadrics(sphere, target);
    ASSERT_TRUE(simplified.ok());
    CompareOptions options;
    options.samples = 50'000;
    auto d = CompareSurfaces(sphere, *simplified, options);
    ASSERT_TRUE(d.ok());
    EXPECT_LT(d->psnr_db, last) << target;
    EXPECT_GT(d->psnr_db, 40.0) << target;
    last = d->psnr_db;
  }
}

// A flat disc: every interior vertex goes at no error, the boundary stays
// vertex for vertex, and the surface is still the disc.
TEST(QuadricSimplification, FlatInteriorGoesAndTheBoundaryStays) {
  const Mesh disc = testing::MakeDisc(12);
  const MeshDiagnosis in = Diagnose(disc);
  auto simplified = SimplifyByQuadrics(disc, 0);
  ASSERT_TRUE(simplified.ok());
  ExpectCleanWithTopologyOf(*simplified, disc);
  EXPECT_EQ(Diagnose(*simplified).boundary_edges, in.boundary_edges);
  EXPECT_LT(simplified->positions.size(), in.boundary_edges + 3);
  for (const Vec3& p : simplified->positions) EXPECT_EQ(p.z(), 0.0);
  auto d = CompareSurfaces(disc, *simplified);
  ASSERT_TRUE(d.ok());
  EXPECT_LT(d->rms, 1e-12);
}

// Nothing closed goes below a tetrahedron's four vertices, and a target above
// the vertex count changes nothing.
TEST(QuadricSimplification, StopsAtTheSmallestClosedSurface) {
  const Mesh cube = testing::MakeCube().mesh;
  auto simplified = SimplifyByQuadrics(cube, 0);
  ASSERT_TRUE(simplified.ok());
  ExpectCleanWithTopologyOf(*simplified, cube);
  EXPECT_GE(simplified->positions.size(), 4u);
  auto same = SimplifyByQuadrics(cube, 100);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->positions, cube.positions);
  EXPECT_EQ(same->faces, cube.faces);
}

TEST(QuadricSimplification, SameInputSameResult) {
  const Mesh torus = testing::MakeTorus(40, 20);
  auto a = SimplifyByQuadrics(torus, 300);
  auto b = SimplifyByQuadrics(torus, 300);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->positions, b->positions);
  EXPECT_EQ(a->faces, b->faces);
}

// Input the remesher's preparation would refuse (three faces on an edge, a
// pinched vertex) is not its contract, but it must not break the simplifier:
// every face of the result indexes a vertex of it.
TEST(QuadricSimplification, NonManifoldInputStaysIndexable) {
  Mesh fin = testing::MakeIcosphere(2);
  const uint32_t a = fin.faces[0][0], b = fin.faces[0][1];
  fin.positions.push_back(Vec3(3.0, 0.0, 0.0));
  fin.faces.push_back({a, b, static_cast<uint32_t>(fin.positions.size() - 1)});
  Mesh pinched = testing::MakeIcosphere(2);
  const Mesh other = testing::MakeIcosphere(2);
  const auto offset = static_cast<uint32_t>(pinched.positions.size());
  for (const Vec3& p : other.positions) pinched.positions.push_back(p + Vec3(2.0, 0.0, 0.0));
  for (Face f : other.faces) {
    for (uint32_t& v : f) v = v == 0 ? 0 : v + offset;  // its vertex 0 is the first sphere's
    pinched.faces.push_back(f);
  }
  for (const Mesh* mesh : {&fin, &pinched}) {
    auto simplified = SimplifyByQuadrics(*mesh, 10);
    ASSERT_TRUE(simplified.ok());
    for (const Face& f : simplified->faces) {
      for (uint32_t v : f) EXPECT_LT(v, simplified->positions.size());
    }
  }
}

TEST(QuadricSimplification, RefusesBadInput) {
  Mesh bad = testing::MakeIcosphere(1);
  bad.faces[3][1] = 1000;
  EXPECT_FALSE(SimplifyByQuadrics(bad, 10).ok());
  Mesh nan = testing::MakeIcosphere(1);
  nan.positions[2].x() = NAN;
  EXPECT_FALSE(SimplifyByQuadrics(nan, 10).ok());
  Mesh repeated = testing::MakeIcosphere(1);
  repeated.faces[0][1] = repeated.faces[0][0];
  EXPECT_FALSE(SimplifyByQuadrics(repeated, 10).ok());
}

}  // namespace
}  // namespace eqmesh

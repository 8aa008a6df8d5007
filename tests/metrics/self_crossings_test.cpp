// Where a mesh passes through itself (metrics/self_crossings.h): none on closed
// surfaces that do not, the faces whose edges cross another face where two
// shapes were modelled into each other, and the crossing points the fold
// reports query by distance.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/triangle_bvh.h"
#include "metrics/self_crossings.h"
#include "test_support.h"

namespace eqmesh {
namespace {

size_t SelfCrossingFaces(const Mesh& mesh) {
  auto bvh = TriangleBvh::Build(mesh);
  EXPECT_TRUE(bvh.ok());
  return bvh.ok() ? CountSelfCrossingFaces(mesh, *bvh) : 0;
}

TEST(SelfCrossings, ClosedSurfacesThatDoNotCrossThemselvesHaveNone) {
  const Mesh torus = testing::MakeTorus(24, 12);
  auto bvh = TriangleBvh::Build(torus);
  ASSERT_TRUE(bvh.ok());
  const StatusOr<SelfCrossingPoints> points = SelfCrossingPoints::Find(torus, *bvh);
  ASSERT_TRUE(points.ok());
  EXPECT_EQ(points->size(), 0u);
  EXPECT_FALSE(points->Within({1, 0, 0}, 10.0));
  EXPECT_EQ(SelfCrossingFaces(testing::MakeIcosphere(3)), 0u);
  EXPECT_EQ(SelfCrossingFaces(testing::MakeTorus(24, 12)), 0u);
  EXPECT_EQ(SelfCrossingFaces(testing::MakeCappedCylinder(0.2, 2.0, 16, 8)), 0u);
  // Two spheres apart, in one mesh.
  const Mesh sphere = testing::MakeIcosphere(2);
  EXPECT_EQ(SelfCrossingFaces(testing::WithComponent(sphere, sphere, {3, 0, 0})), 0u);
}

// A big triangle in z = 0 and a small upright one through it: both edges of
// the small one that reach below z = 0 pierce the big one, none of the big
// one's edges pierces the small one.
TEST(SelfCrossings, AnEdgeThroughAFaceMarksTheEdgesFace) {
  Mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}, {0.3, 0.2, 1}};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  auto bvh = TriangleBvh::Build(m);
  ASSERT_TRUE(bvh.ok());
  EXPECT_FALSE(EdgeCrossesAnotherFace(m, *bvh, 0));
  EXPECT_TRUE(EdgeCrossesAnotherFace(m, *bvh, 1));
  EXPECT_EQ(CountSelfCrossingFaces(m, *bvh), 1u);
  // The crossings lie at (0, 0, 0) and (0.15, 0.1, 0), each found from both
  // ends of its edge.
  const StatusOr<SelfCrossingPoints> points = SelfCrossingPoints::Find(m, *bvh);
  ASSERT_TRUE(points.ok());
  EXPECT_EQ(points->size(), 4u);
  EXPECT_TRUE(points->Within({0.0, 0.0, 0.05}, 0.1));
  EXPECT_TRUE(points->Within({0.15, 0.1, 0.0}, 1e-9));
  EXPECT_FALSE(points->Within({0.6, -0.6, 0.0}, 0.3));
  // Within the radius of p lies part of the big face, but no crossing.
  EXPECT_FALSE(points->Within({0.1, 0.5, 0.3}, 0.35));
}

// Two unit spheres whose centres are one apart cross on a circle of radius
// sqrt(3)/2 in the plane x = 1/2.
TEST(SelfCrossings, InterpenetratingSpheresCrossOnTheirCircle) {
  const Mesh sphere = testing::MakeIcosphere(3);
  const Mesh both = testing::WithComponent(sphere, sphere, {1, 0, 0});
  auto bvh = TriangleBvh::Build(both);
  ASSERT_TRUE(bvh.ok());
  const size_t crossing = CountSelfCrossingFaces(both, *bvh);
  EXPECT_GT(crossing, 0u);
  EXPECT_LT(crossing, both.faces.size() / 4);  // a band along the circle
  const double r = std::sqrt(3.0) / 2.0;
  const StatusOr<SelfCrossingPoints> points = SelfCrossingPoints::Find(both, *bvh);
  ASSERT_TRUE(points.ok());
  EXPECT_TRUE(points->Within({0.5, r, 0.0}, 0.1));
  EXPECT_TRUE(points->Within({0.5, 0.0, -r}, 0.1));
  EXPECT_FALSE(points->Within({-1.0, 0.0, 0.0}, 0.5));
  EXPECT_FALSE(points->Within({0.5, 0.0, 0.0}, 0.5));  // the lens' middle
}

}  // namespace
}  // namespace eqmesh

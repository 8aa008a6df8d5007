// Triangle quality and the sliver count behind `eqmesh remesh --json`'s
// sliver_faces and the placement repair's shape score.
#include <gtest/gtest.h>

#include <cmath>

#include "remesh/quality_checks.h"

namespace eqmesh {
namespace {

TEST(TriangleQuality, IsOneForEquilateralAndZeroForDegenerate) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2.0, 0);
  EXPECT_NEAR(TriangleQuality(a, b, c), 1.0, 1e-12);
  EXPECT_EQ(TriangleQuality(a, b, Vec3(2, 0, 0)), 0.0);  // collinear
  EXPECT_EQ(TriangleQuality(a, a, a), 0.0);              // a point, no division by zero
}

TEST(TriangleQuality, RightIsoscelesAndInvariantUnderScaleAndOrientation) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // 4*sqrt(3) * (1/2) / (1 + 2 + 1)
  EXPECT_NEAR(TriangleQuality(a, b, c), std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_NEAR(TriangleQuality(a, c, b), std::sqrt(3.0) / 2.0, 1e-12);  // either winding
  EXPECT_NEAR(TriangleQuality(1e-6 * a, 1e-6 * b, 1e-6 * c), std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_NEAR(TriangleQuality(1e6 * a + Vec3(3, 4, 5), 1e6 * b + Vec3(3, 4, 5), 1e6 * c + Vec3(3, 4, 5)),
              std::sqrt(3.0) / 2.0, 1e-9);
}

TEST(CountSlivers, CountsFacesBelowTheSliverQuality) {
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, std::sqrt(3.0) / 2.0, 0),  // equilateral
                 Vec3(0.5, 0.01, 0),                                                 // a needle's apex
                 Vec3(0.5, 0.1, 0)};                                                 // a flat but fair apex
  m.faces = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};
  ASSERT_LT(TriangleQuality(m.positions[0], m.positions[1], m.positions[3]), kSliverQuality);
  ASSERT_GE(TriangleQuality(m.positions[0], m.positions[1], m.positions[4]), kSliverQuality);
  EXPECT_EQ(CountSlivers(m), 1u);
  m.faces.push_back({3, 1, 0});
  EXPECT_EQ(CountSlivers(m), 2u);
  EXPECT_EQ(CountSlivers(Mesh()), 0u);
}

}  // namespace
}  // namespace eqmesh

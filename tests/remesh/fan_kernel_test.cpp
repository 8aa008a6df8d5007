// FanKernelCenter: the point of a flattened fan farthest from inverting a face.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "remesh/fan_kernel.h"

namespace eqmesh {
namespace {

// Opposite edges of a regular n-gon fan around the origin in the z = 0 plane,
// counter-clockwise seen from +z.
std::vector<std::pair<Vec3, Vec3>> RegularFan(int n, double radius) {
  std::vector<std::pair<Vec3, Vec3>> opposite;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n, b = 2.0 * M_PI * (i + 1) / n;
    opposite.emplace_back(Vec3(radius * std::cos(a), radius * std::sin(a), 0),
                          Vec3(radius * std::cos(b), radius * std::sin(b), 0));
  }
  return opposite;
}

double SmallestSignedArea(const Vec3& apex, const std::vector<std::pair<Vec3, Vec3>>& opposite) {
  double smallest = INFINITY;
  for (const auto& [a, b] : opposite) smallest = std::min(smallest, (a - apex).cross(b - apex).z());
  return smallest;
}

TEST(FanKernel, FoldedApexOfARegularFanGoesToItsCentre) {
  const auto fan = RegularFan(6, 1.0);
  // An apex outside the ring folds some of its faces.
  const Vec3 folded(1.7, 0.4, 0.3);
  ASSERT_LT(SmallestSignedArea(folded, fan), 0.0);
  const auto centre = FanKernelCenter(folded, Vec3(0, 0, 2), fan);
  ASSERT_TRUE(centre.has_value());
  // On the plane through the apex, over the ring's centre.
  EXPECT_NEAR(centre->x(), 0.0, 1e-12);
  EXPECT_NEAR(centre->y(), 0.0, 1e-12);
  EXPECT_NEAR(centre->z(), 0.3, 1e-12);
  EXPECT_GT(SmallestSignedArea(*centre, fan), 0.0);
}

TEST(FanKernel, NonConvexStarShapedRingGetsAPointThatUnfoldsEveryFace) {
  // A star polygon: every other ring vertex pulled in; its kernel is a small
  // hexagon around the origin, off-centre of the vertices' mean.
  std::vector<Vec3> ring;
  for (int i = 0; i < 12; ++i) {
    const double a = 2.0 * M_PI * i / 12, r = i % 2 ? 0.35 : 1.0;
    ring.emplace_back(r * std::cos(a) + 0.2, r * std::sin(a), 0);
  }
  std::vector<std::pair<Vec3, Vec3>> fan;
  for (size_t i = 0; i < ring.size(); ++i) fan.emplace_back(ring[i], ring[(i + 1) % ring.size()]);
  const auto centre = FanKernelCenter(Vec3(-0.9, 0.8, 0), Vec3(0, 0, 1), fan);
  ASSERT_TRUE(centre.has_value());
  EXPECT_GT(SmallestSignedArea(*centre, fan), 0.0);
}

TEST(FanKernel, DegenerateFansGiveNothing) {
  EXPECT_FALSE(FanKernelCenter(Vec3::Zero(), Vec3(0, 0, 1), {}).has_value());
  const auto fan = RegularFan(6, 1.0);
  EXPECT_FALSE(FanKernelCenter(Vec3::Zero(), Vec3::Zero(), fan).has_value());
  // All opposite edges collapsed to points.
  std::vector<std::pair<Vec3, Vec3>> points(5, {Vec3(1, 0, 0), Vec3(1, 0, 0)});
  EXPECT_FALSE(FanKernelCenter(Vec3::Zero(), Vec3(0, 0, 1), points).has_value());
}

}  // namespace
}  // namespace eqmesh

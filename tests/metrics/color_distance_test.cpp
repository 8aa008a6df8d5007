// The appearance meter (metrics/color_distance.h) on synthetic coloured spheres.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/color_distance.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// Colour as a function of the surface point: a smooth RGB ramp plus `offset`.
SurfaceColor Ramp(const Mesh& mesh, double offset) {
  return [&mesh, offset](uint32_t face, const std::array<double, 3>& b) {
    Vec3 p = Vec3::Zero();
    for (size_t k = 0; k < 3; ++k) p += b[k] * mesh.positions[mesh.faces[face][k]];
    return std::array<double, 3>{127.5 + 100 * p.x() + offset, 127.5 + 100 * p.y() + offset, 127.5 + offset};
  };
}

TEST(ColorDistance, IdenticalColouringMeasuresNoError) {
  const Mesh sphere = testing::MakeIcosphere(3);
  auto d = CompareColors(sphere, Ramp(sphere, 0), sphere, Ramp(sphere, 0), {20000});
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_LT(d->rms, 1e-6);
  EXPECT_GT(d->psnr_db, 120.0);
}

TEST(ColorDistance, AConstantShiftIsItsOwnRmsInBothDirections) {
  const Mesh sphere = testing::MakeIcosphere(3);
  auto d = CompareColors(sphere, Ramp(sphere, 0), sphere, Ramp(sphere, 10), {20000});
  ASSERT_TRUE(d.ok());
  EXPECT_NEAR(d->rms_ab, 10.0, 1e-6);
  EXPECT_NEAR(d->rms_ba, 10.0, 1e-6);
  EXPECT_NEAR(d->psnr_db, 20 * std::log10(25.5), 1e-6);
}

TEST(ColorDistance, ACoarserSurfaceReadsTheColourAtItsClosestPoints) {
  // The same ramp on a finer and a coarser sphere differs only through the
  // geometry (a few units of 255), and the worse direction is reported.
  const Mesh fine = testing::MakeIcosphere(4), coarse = testing::MakeIcosphere(2);
  auto d = CompareColors(fine, Ramp(fine, 0), coarse, Ramp(coarse, 0), {50000});
  ASSERT_TRUE(d.ok());
  EXPECT_GT(d->rms, 0.1);
  EXPECT_LT(d->rms, 5.0);
  EXPECT_EQ(d->rms, std::max(d->rms_ab, d->rms_ba));
}

TEST(ColorDistance, ResultsDoNotDependOnTheThreadCount) {
  const Mesh fine = testing::MakeIcosphere(4), coarse = testing::MakeIcosphere(2);
  auto one = CompareColors(fine, Ramp(fine, 0), coarse, Ramp(coarse, 3), {30000, 7, 1});
  auto many = CompareColors(fine, Ramp(fine, 0), coarse, Ramp(coarse, 3), {30000, 7, 4});
  ASSERT_TRUE(one.ok() && many.ok());
  EXPECT_EQ(one->rms_ab, many->rms_ab);
  EXPECT_EQ(one->rms_ba, many->rms_ba);
}

}  // namespace
}  // namespace eqmesh

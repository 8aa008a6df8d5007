// Triangle quality and the sliver count behind `eqmesh remesh --json`'s
// sliver_faces and the placement repair's shape score; the fold test on inputs
// of several parts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "mesh/triangle_bvh.h"
#include "remesh/quality_checks.h"
#include "test_support.h"

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

// Part A: a roof over the y axis (two slopes meeting at a ridge at z = 0.5),
// facing up. Part B: a plate at z = 0.3 under the ridge, facing down, as where
// two parts of an asset interpenetrate.
Mesh RoofWithPlateUnderItsRidge() {
  Mesh m;
  m.positions = {Vec3(-1, -1, 0),     Vec3(-1, 1, 0),     Vec3(0, -1, 0.5),  Vec3(0, 1, 0.5),
                 Vec3(1, -1, 0),      Vec3(1, 1, 0),      Vec3(-0.1, -0.5, 0.3), Vec3(0.1, -0.5, 0.3),
                 Vec3(0.1, 0.5, 0.3), Vec3(-0.1, 0.5, 0.3)};
  m.faces = {{0, 2, 3}, {0, 3, 1}, {2, 4, 5}, {2, 5, 3},  // roof
             {6, 8, 7}, {6, 9, 8}};                       // plate
  return m;
}

TEST(FacesAwayFromInput, JudgesAFaceAgainstThePartItRemeshes) {
  const Mesh input = RoofWithPlateUnderItsRidge();
  auto bvh = TriangleBvh::Build(input);
  ASSERT_TRUE(bvh.ok());
  const std::vector<uint32_t> parts = FacePartsForFoldTest(input);
  ASSERT_EQ(parts.size(), input.faces.size());
  EXPECT_NE(parts[0], parts[4]);
  // Corners on the roof (two on the slopes, one on the ridge), facing up like
  // it; its centroid (z = 1/3) is nearer the plate (z = 0.3) than the slopes.
  const Vec3 a(-0.5, -0.2, 0.25), b(0.5, -0.2, 0.25), c(0, 0.3, 0.5);
  ASSERT_GT((b - a).cross(c - a).z(), 0.0);
  const uint32_t roof = parts[0];
  EXPECT_TRUE(FacesAwayFromInput(*bvh, input, {}, kAnyPart, a, b, c));  // judged against the plate
  EXPECT_TRUE(FacesAwayFromInput(*bvh, input, parts, kAnyPart, a, b, c));
  EXPECT_FALSE(FacesAwayFromInput(*bvh, input, parts, roof, a, b, c));
  EXPECT_TRUE(FacesAwayFromInput(*bvh, input, parts, roof, a, c, b));  // turned over, it folds on its part
  EXPECT_TRUE(FacesAwayFromInput(*bvh, input, parts, parts[4], a, b, c));
  Mesh remesh;
  remesh.positions = {a, b, c};
  remesh.faces = {{0, 1, 2}};
  const StatusOr<FoldReport> folds = CountFoldsAgainstInput(remesh, input);
  ASSERT_TRUE(folds.ok());
  EXPECT_EQ(folds->flipped_faces, 0u);
}

// A 10 x 10 grid on z = 0 facing up, and a scan patch lying on it facing down,
// as small patches of a scan lie on its body.
Mesh GridWithPatchOnIt() {
  Mesh m;
  for (int y = 0; y <= 10; ++y) {
    for (int x = 0; x <= 10; ++x) m.positions.push_back(Vec3(0.1 * x, 0.1 * y, 0.0));
  }
  for (uint32_t y = 0; y < 10; ++y) {
    for (uint32_t x = 0; x < 10; ++x) {
      const uint32_t v = 11 * y + x;
      m.faces.push_back({v, v + 1, v + 12});
      m.faces.push_back({v, v + 12, v + 11});
    }
  }
  const uint32_t p = static_cast<uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), {Vec3(0.25, 0.25, 1e-9), Vec3(0.75, 0.25, 1e-9), Vec3(0.75, 0.75, 1e-9),
                                         Vec3(0.25, 0.75, 1e-9)});
  m.faces.push_back({p, p + 2, p + 1});
  m.faces.push_back({p, p + 3, p + 2});
  return m;
}

// A remesh of the grid lying a hair above it (nearer the patch than the grid
// where the patch is) is judged against the grid, the part most of it lies on,
// though all three corners of its faces over the patch lie nearer the patch.
TEST(CountFoldsAgainstInput, JudgesEachPartOfTheRemeshAgainstTheInputPartUnderMostOfIt) {
  const Mesh input = GridWithPatchOnIt();
  Mesh remesh = input;
  remesh.positions.resize(121);
  remesh.faces.resize(200);
  for (Vec3& p : remesh.positions) p.z() = 2e-9;
  const StatusOr<FoldReport> folds = CountFoldsAgainstInput(remesh, input);
  ASSERT_TRUE(folds.ok());
  EXPECT_EQ(folds->flipped_faces, 0u);
  // Face by face against the whole input, the faces over the patch fold.
  auto bvh = TriangleBvh::Build(input);
  ASSERT_TRUE(bvh.ok());
  size_t over_patch = 0;
  for (const Face& f : remesh.faces) {
    over_patch += FacesAwayFromInput(*bvh, input, {}, kAnyPart, remesh.positions[f[0]], remesh.positions[f[1]],
                                     remesh.positions[f[2]]);
  }
  EXPECT_GT(over_patch, 0u);
}

// The face of `mesh` whose centroid lies nearest p.
uint32_t FaceNearest(const Mesh& mesh, const Vec3& p) {
  uint32_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 c = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
    if ((c - p).squaredNorm() < best_d2) best_d2 = (c - p).squaredNorm(), best = f;
  }
  return best;
}

// Two spheres modelled into each other cross on a circle in x = 1/2: of two
// faces of the remesh turned over, the one beside that circle is counted as
// near where the input crosses itself, the one on the far side is not.
TEST(CountFoldsAgainstInput, SaysWhichFlippedFacesLieWhereTheInputCrossesItself) {
  const Mesh sphere = testing::MakeIcosphere(3);
  const Mesh input = testing::WithComponent(sphere, sphere, {1, 0, 0});
  Mesh remesh = input;
  for (const Vec3& p : {Vec3(0.5, std::sqrt(3.0) / 2.0, 0.0), Vec3(-1.0, 0.0, 0.0)}) {
    Face& f = remesh.faces[FaceNearest(sphere, p)];
    std::swap(f[1], f[2]);
  }
  const StatusOr<FoldReport> folds = CountFoldsAgainstInput(remesh, input);
  ASSERT_TRUE(folds.ok());
  EXPECT_EQ(folds->flipped_faces, 2u);
  EXPECT_EQ(folds->flipped_near_self_crossings, 1u);
}

TEST(FacePartsForFoldTest, IsEmptyForAnInputOfOnePart) {
  Mesh roof = RoofWithPlateUnderItsRidge();
  roof.faces.resize(4);
  roof.positions.resize(6);
  EXPECT_TRUE(FacePartsForFoldTest(roof).empty());
}

}  // namespace
}  // namespace eqmesh

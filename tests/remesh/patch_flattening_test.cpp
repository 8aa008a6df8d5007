#include "remesh/patch_flattening.h"

#include <gtest/gtest.h>

#include <utility>

#include "mesh/triangle_bvh.h"
#include "remesh/remesh.h"
#include "remesh_checks.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// A fold planted in a clean sphere remesh (two corners of a finest face
// swapped, which turns it and its neighbours over) is refilled away, and only
// vertices refinement created move.
TEST(PatchFlattening, RefillsAPlantedFoldAndMovesOnlyRefinedVertices) {
  const Mesh sphere = testing::MakeIcosphere(4);
  RemeshOptions options;
  options.levels = 3;
  auto remeshed = Remesh(sphere, options, nullptr);
  ASSERT_TRUE(remeshed.ok()) << remeshed.status().message();
  SemiRegularMesh sr = std::move(*remeshed);
  const int levels = sr.hierarchy.levels();
  ASSERT_EQ(testing::CountFlips(ExtractLevel(sr, levels), sphere).flipped, 0u);

  // Child 3 of a level-(L-1) face has three finest odd corners.
  const Face inner = sr.hierarchy.Faces(levels)[4 * 7 + 3];
  std::swap(sr.positions[inner[0]], sr.positions[inner[1]]);
  const testing::FlipCount planted = testing::CountFlips(ExtractLevel(sr, levels), sphere);
  ASSERT_GT(planted.flipped + planted.degenerate, 0u);

  auto bvh = TriangleBvh::Build(sphere);
  ASSERT_TRUE(bvh.ok());
  const InputSurface surface(sphere, *bvh, std::vector<uint8_t>(sphere.positions.size(), 0));
  std::vector<uint32_t> candidates(sr.hierarchy.Faces(levels).size());
  for (uint32_t f = 0; f < candidates.size(); ++f) candidates[f] = f;
  const std::vector<Vec3> before = sr.positions;
  StencilCache stencils(sr.hierarchy);
  const FaceIncidence finest_faces = BuildFaceIncidence(sr.hierarchy.Faces(levels), sr.positions.size());
  const std::vector<uint8_t> moved =
      FlattenFoldedPatches(sr.hierarchy, surface, RemeshParts(), sr.kinds, candidates, finest_faces, &stencils,
                           &sr.positions);

  const testing::FlipCount after = testing::CountFlips(ExtractLevel(sr, levels), sphere);
  EXPECT_EQ(after.flipped + after.degenerate, 0u);
  ASSERT_EQ(moved.size(), sr.positions.size());
  size_t moved_count = 0;
  for (uint32_t v = 0; v < moved.size(); ++v) {
    moved_count += moved[v];
    if (!moved[v]) {
      EXPECT_EQ(sr.positions[v], before[v]) << "vertex " << v << " moved unreported";
    }
    if (v < sr.hierarchy.NumVertices(levels - 3)) {
      EXPECT_FALSE(moved[v]) << "vertex " << v << " is too coarse";
    }
  }
  EXPECT_GT(moved_count, 0u);
  EXPECT_LE(moved_count, 64u);
}

}  // namespace
}  // namespace eqmesh

// The butterfly's crease rules (butterfly.cpp C1-C3) and the hierarchy's crease
// tags (semi_regular.h): a cube refined at its edges' midpoints is exactly what
// the prediction gives once its twelve edges are tagged, and not without.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mesh/semi_regular.h"
#include "test_support.h"
#include "wavelet/butterfly.h"
#include "wavelet/transform.h"

namespace eqmesh {
namespace {

using testing::MakeCube;

// Every level's odd vertices at their edge's midpoint: the cube itself.
std::vector<Vec3> MidpointRefinement(const SemiRegularHierarchy& h, std::vector<Vec3> positions) {
  for (int j = 0; j < h.levels(); ++j) {
    for (const Edge& e : h.OddEdges(j)) positions.push_back(0.5 * (positions[e[0]] + positions[e[1]]));
  }
  return positions;
}

double LargestDetail(const SemiRegularHierarchy& h, const std::vector<Vec3>& positions) {
  const WaveletCoefficients c = ForwardTransform(h, positions, WaveletKind::kUnlifted);
  double largest = 0.0;
  for (const auto& level : c.details) {
    for (const Vec3& d : level) largest = std::max(largest, d.norm());
  }
  return largest;
}

TEST(CreaseRules, ACubeRefinedAtMidpointsIsPredictedExactlyWithItsEdgesTagged) {
  const testing::CubeWithEdges cube = MakeCube();
  auto h = SemiRegularHierarchy::Build(8, cube.mesh.faces, 4);
  ASSERT_TRUE(h.ok()) << h.status().ToString();
  const std::vector<Vec3> positions = MidpointRefinement(*h, cube.mesh.positions);
  // Untagged, the butterfly rounds the cube's edges: every level has details.
  EXPECT_GT(LargestDetail(*h, positions), 0.01);
  ASSERT_TRUE(h->SetBaseCreases(cube.edges).ok());
  EXPECT_LT(LargestDetail(*h, positions), 1e-12);
}

TEST(CreaseRules, TagsAreTheHalvesOfTaggedEdgesAtEveryLevel) {
  const testing::CubeWithEdges cube = MakeCube();
  auto tagged_first = SemiRegularHierarchy::Build(8, cube.mesh.faces, 0);
  ASSERT_TRUE(tagged_first.ok());
  // Tags on the base, either orientation, repeated: twelve edges.
  std::vector<Edge> edges = cube.edges;
  edges.push_back({cube.edges[0][1], cube.edges[0][0]});
  ASSERT_TRUE(tagged_first->SetBaseCreases(edges).ok());
  EXPECT_EQ(tagged_first->BaseCreases().size(), 12u);
  for (int j = 0; j < 3; ++j) ASSERT_TRUE(tagged_first->Refine().ok());
  // Tagging after refining gives the same tags.
  auto tagged_after = SemiRegularHierarchy::Build(8, cube.mesh.faces, 3);
  ASSERT_TRUE(tagged_after.ok());
  ASSERT_TRUE(tagged_after->SetBaseCreases(cube.edges).ok());
  for (int j = 0; j < 3; ++j) {
    uint32_t count = 0;
    for (uint32_t k = 0; k < tagged_first->NumOddVertices(j); ++k) {
      EXPECT_EQ(tagged_first->IsCreaseOdd(j, k), tagged_after->IsCreaseOdd(j, k));
      count += tagged_first->IsCreaseOdd(j, k);
      if (j == 0 || !tagged_first->IsCreaseOdd(j, k)) continue;
      // A tagged edge has one end on a tagged edge of the level before, the
      // other at that edge's odd vertex.
      const Edge& e = tagged_first->OddEdge(j, k);
      const uint32_t first_new = tagged_first->NumVertices(j - 1);
      const uint32_t m = std::max(e[0], e[1]), other = std::min(e[0], e[1]);
      ASSERT_GE(m, first_new);
      EXPECT_TRUE(tagged_first->IsCreaseOdd(j - 1, m - first_new));
      const Edge& parent = tagged_first->OddEdge(j - 1, m - first_new);
      EXPECT_TRUE(other == parent[0] || other == parent[1]);
    }
    EXPECT_EQ(count, 12u << j) << "level " << j;  // each tagged edge halves
  }
}

TEST(CreaseRules, ATagOffTheBaseIsRefused) {
  const testing::CubeWithEdges cube = MakeCube();
  auto h = SemiRegularHierarchy::Build(8, cube.mesh.faces, 1);
  ASSERT_TRUE(h.ok());
  EXPECT_EQ(h->SetBaseCreases({{0, 7}}).code(), StatusCode::kInvalidMesh);  // a diagonal through the cube
  EXPECT_FALSE(h->HasCreases());
}

TEST(CreaseRules, ATaggedEdgeFollowsItsCreaseNeighboursAndEndsLikeAStraightCurve) {
  // A path of three tagged edges along the cube's bottom, 0-2-3-1: the middle
  // edge (2, 3) takes -1/16 of the path's next vertices 0 and 1 (rule C1); at
  // the path's end 0 the ghost 2*0 - 2 stands in for the missing neighbour.
  const testing::CubeWithEdges cube = MakeCube();
  auto h = SemiRegularHierarchy::Build(8, cube.mesh.faces, 1);
  ASSERT_TRUE(h.ok());
  ASSERT_TRUE(h->SetBaseCreases({{0, 2}, {2, 3}, {3, 1}}).ok());
  const ButterflyPredictor predictor(*h, 0);
  for (uint32_t k = 0; k < h->NumOddVertices(0); ++k) {
    const Edge& e = h->OddEdge(0, k);
    const Edge key{std::min(e[0], e[1]), std::max(e[0], e[1])};
    EXPECT_NEAR(predictor.Stencil(k).Apply(std::vector<Vec3>(8, Vec3(1, 1, 1))).x(), 1.0, 1e-15);
    std::vector<double> w(8, 0.0);
    for (uint32_t v = 0; v < 8; ++v) {
      std::vector<Vec3> basis(8, Vec3::Zero());
      basis[v] = Vec3(1, 0, 0);
      w[v] = predictor.Stencil(k).Apply(basis).x();
    }
    if (key == Edge{2, 3}) {
      EXPECT_DOUBLE_EQ(w[2], 9.0 / 16.0);
      EXPECT_DOUBLE_EQ(w[3], 9.0 / 16.0);
      EXPECT_DOUBLE_EQ(w[0], -1.0 / 16.0);
      EXPECT_DOUBLE_EQ(w[1], -1.0 / 16.0);
    } else if (key == Edge{0, 2}) {
      EXPECT_DOUBLE_EQ(w[0], 9.0 / 16.0 - 2.0 / 16.0);
      EXPECT_DOUBLE_EQ(w[2], 9.0 / 16.0 + 1.0 / 16.0);
      EXPECT_DOUBLE_EQ(w[3], -1.0 / 16.0);
    }
  }
}

}  // namespace
}  // namespace eqmesh

#include <gtest/gtest.h>

#include <map>

#include "mesh/semi_regular.h"
#include "test_support.h"

namespace eqmesh {
namespace {

std::map<std::pair<uint32_t, uint32_t>, int> DirectedEdgeCounts(const std::vector<Face>& faces) {
  std::map<std::pair<uint32_t, uint32_t>, int> counts;
  for (const Face& f : faces)
    for (int i = 0; i < 3; ++i) counts[{f[i], f[(i + 1) % 3]}]++;
  return counts;
}

TEST(SemiRegularHierarchy, CountsFollowEulerOnClosedMesh) {
  const Mesh ico = testing::MakeIcosphere(0);
  auto h = SemiRegularHierarchy::Build(12, ico.faces, 3);
  ASSERT_TRUE(h.ok()) << h.status().ToString();
  for (int j = 0; j <= 3; ++j) {
    const uint64_t f = h->Faces(j).size();
    EXPECT_EQ(f, 20u << (2 * j));
    // Closed genus 0: V = F/2 + 2.
    EXPECT_EQ(h->NumVertices(j), f / 2 + 2);
  }
}

TEST(SemiRegularHierarchy, ChildrenKeepOrientationAndNesting) {
  const Mesh ico = testing::MakeIcosphere(0);
  auto h = SemiRegularHierarchy::Build(12, ico.faces, 2);
  ASSERT_TRUE(h.ok());
  for (int j = 0; j < 2; ++j) {
    const auto& coarse = h->Faces(j);
    const auto& fine = h->Faces(j + 1);
    for (size_t f = 0; f < coarse.size(); ++f) {
      // Corner children keep the coarse corner in the same slot.
      EXPECT_EQ(fine[4 * f + 0][0], coarse[f][0]);
      EXPECT_EQ(fine[4 * f + 1][1], coarse[f][1]);
      EXPECT_EQ(fine[4 * f + 2][2], coarse[f][2]);
    }
    // Each directed edge appears once: consistently oriented manifold.
    for (const auto& [edge, count] : DirectedEdgeCounts(fine)) EXPECT_EQ(count, 1);
    for (uint32_t k = 0; k < h->NumOddVertices(j); ++k) {
      const Edge& e = h->OddEdge(j, k);
      EXPECT_LT(e[0], h->NumVertices(j));
      EXPECT_LT(e[1], h->NumVertices(j));
      EXPECT_EQ(h->VertexLevel(h->NumVertices(j) + k), j + 1);
    }
  }
}

TEST(SemiRegularHierarchy, RejectsBadBaseAndHugeCounts) {
  EXPECT_FALSE(SemiRegularHierarchy::Build(3, {{0, 1, 3}}, 1).ok());
  EXPECT_FALSE(SemiRegularHierarchy::Build(3, {{0, 1, 1}}, 1).ok());
  EXPECT_EQ(SemiRegularHierarchy::Build(3, {{0, 1, 2}}, 15, 1u << 20).status().code(),
            StatusCode::kResourceLimit);
  EXPECT_FALSE(SemiRegularHierarchy::Build(3, {{0, 1, 2}}, -1).ok());
}

TEST(SemiRegularHierarchy, ExtractLevelAppendsKeptComponents) {
  SemiRegularMesh m;
  m.hierarchy = *SemiRegularHierarchy::Build(3, {{0, 1, 2}}, 1);
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {.5, 0, 0}, {.5, .5, 0}, {0, .5, 0}};
  m.kept_exactly.positions = {{5, 5, 5}, {6, 5, 5}, {5, 6, 5}};
  m.kept_exactly.faces = {{0, 1, 2}};
  const Mesh level1 = ExtractLevel(m, 1);
  EXPECT_EQ(level1.positions.size(), 9u);
  EXPECT_EQ(level1.faces.size(), 5u);
  EXPECT_EQ(level1.faces.back()[0], 6u);
  const Mesh level0 = ExtractLevel(m, 0);
  EXPECT_EQ(level0.positions.size(), 6u);
  EXPECT_EQ(level0.faces.size(), 2u);
}

}  // namespace
}  // namespace eqmesh

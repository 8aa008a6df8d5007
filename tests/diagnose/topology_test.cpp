#include <gtest/gtest.h>

#include <set>

#include "diagnose/synthetic_cases.h"
#include "mesh/mesh_topology.h"
#include "test_support.h"

namespace eqmesh {
namespace {

TEST(MeshTopology, ClosedIcosphereHasTwoFacesPerEdgeAndOneFanPerVertex) {
  const Mesh m = testing::MakeIcosphere(2);
  const MeshTopology t(m);
  EXPECT_EQ(t.num_edges(), 30u * 16u);
  EXPECT_EQ(t.num_components(), 1u);
  std::vector<uint32_t> labels;
  for (uint32_t e = 0; e < t.num_edges(); ++e) {
    EXPECT_EQ(t.EdgeFaceCount(e), 2u);
    EXPECT_FALSE(t.IsInconsistentEdge(e));
    const Edge& ab = t.EdgeVertices(e);
    EXPECT_LT(ab[0], ab[1]);
    EXPECT_EQ(t.FindEdge(ab[1], ab[0]), e);
  }
  for (uint32_t v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(t.VertexFans(v, &labels), 1u);
  EXPECT_TRUE(t.BoundaryLoops().empty());
  EXPECT_EQ(t.PlanConsistentOrientation().faces_to_flip, 0u);
}

TEST(MeshTopology, HalfedgesOfAnEdgeJoinItsEndpoints) {
  const Mesh m = testing::MakeTorus(8, 6);
  const MeshTopology t(m);
  for (uint32_t e = 0; e < t.num_edges(); ++e) {
    const Edge& ab = t.EdgeVertices(e);
    for (uint32_t h : t.EdgeHalfedges(e)) {
      EXPECT_EQ(t.HalfedgeEdge(h), e);
      const std::set<uint32_t> ends{t.HalfedgeFrom(h), t.HalfedgeTo(h)};
      EXPECT_EQ(ends, (std::set<uint32_t>{ab[0], ab[1]}));
    }
  }
  EXPECT_EQ(t.FindEdge(0, 0), MeshTopology::kNone);
}

TEST(MeshTopology, DiscBoundaryIsOneOrderedCycle) {
  const int rings = 4;
  const Mesh m = testing::MakeDisc(rings);
  const MeshTopology t(m);
  const auto loops = t.BoundaryLoops();
  ASSERT_EQ(loops.size(), 1u);
  const BoundaryLoop& loop = loops[0];
  EXPECT_TRUE(loop.closed);
  ASSERT_EQ(loop.vertices.size(), static_cast<size_t>(6 * rings));
  ASSERT_EQ(loop.edges.size(), loop.vertices.size());
  for (size_t k = 0; k < loop.vertices.size(); ++k) {
    const uint32_t a = loop.vertices[k], b = loop.vertices[(k + 1) % loop.vertices.size()];
    EXPECT_EQ(t.FindEdge(a, b), loop.edges[k]);
    EXPECT_TRUE(t.IsBoundaryEdge(loop.edges[k]));
  }
  // The loop follows the faces' orientation: its first edge is a face half-edge a -> b.
  const uint32_t h = t.EdgeHalfedges(loop.edges[0])[0];
  EXPECT_EQ(t.HalfedgeFrom(h), loop.vertices[0]);
}

TEST(MeshTopology, BowtieHasTwoFansAndTwoLoops) {
  const Mesh m = testing::MakeBowtie();
  const MeshTopology t(m);
  std::vector<uint32_t> labels;
  EXPECT_EQ(t.VertexFans(0, &labels), 2u);
  EXPECT_EQ(labels, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(t.num_components(), 2u);
  const auto loops = t.BoundaryLoops();
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].vertices.size(), 3u);
  EXPECT_EQ(loops[1].vertices.size(), 3u);
  EXPECT_NE(loops[0].component, loops[1].component);
}

TEST(MeshTopology, CutMaskSeparatesFans) {
  const Mesh m = testing::MakeDisc(2);
  const MeshTopology t(m);
  std::vector<uint32_t> labels;
  ASSERT_EQ(t.VertexFans(0, &labels), 1u);
  // Cut two spokes of the centre: its fan falls apart in two.
  std::vector<uint8_t> cut(m.num_faces(), 0);
  int cuts = 0;
  for (uint32_t f : t.VertexFaces(0)) {
    const Face& tri = m.faces[f];
    for (int i = 0; i < 3; ++i) {
      const bool spoke = tri[i] == 0 && (tri[(i + 1) % 3] == 1 || tri[(i + 1) % 3] == 4);
      const bool spoke_in = tri[(i + 1) % 3] == 0 && (tri[i] == 1 || tri[i] == 4);
      if (spoke || spoke_in) {
        cut[f] |= static_cast<uint8_t>(1u << i);
        ++cuts;
      }
    }
  }
  EXPECT_EQ(cuts, 4);  // two edges, two faces each
  EXPECT_EQ(t.VertexFans(0, &labels, &cut), 2u);
}

TEST(MeshTopology, UnusableFacesTakePartInNothing) {
  Mesh m = testing::MakeTriangle();
  m.faces.push_back({0, 0, 1});
  m.faces.push_back({0, 1, 7});
  const MeshTopology t(m);
  EXPECT_EQ(t.num_unusable_faces(), 2u);
  EXPECT_EQ(t.num_edges(), 3u);
  EXPECT_EQ(t.num_components(), 1u);
  EXPECT_EQ(t.FaceComponents()[1], MeshTopology::kNone);
  EXPECT_EQ(t.VertexFaces(0).size(), 1u);
}

TEST(MeshTopology, OrientationPlanFlipsTheOddFaceOut) {
  const Mesh m = testing::MakeSphereWithFlippedFace(17);
  const OrientationPlan plan = MeshTopology(m).PlanConsistentOrientation();
  EXPECT_TRUE(plan.conflict_edges.empty());
  EXPECT_EQ(plan.faces_to_flip, 1u);
  EXPECT_EQ(plan.flip[17], 1u);
}

TEST(MeshTopology, MobiusStripIsNotOrientable) {
  const Mesh m = testing::MakeMobiusStrip(12);
  const MeshTopology t(m);
  EXPECT_FALSE(t.PlanConsistentOrientation().conflict_edges.empty());
  ASSERT_EQ(t.BoundaryLoops().size(), 1u);
  EXPECT_EQ(t.BoundaryLoops()[0].vertices.size(), 24u);
}

TEST(MeshTopology, EmptyMesh) {
  const MeshTopology t{Mesh{}};
  EXPECT_EQ(t.num_edges(), 0u);
  EXPECT_EQ(t.num_components(), 0u);
  EXPECT_TRUE(t.BoundaryLoops().empty());
}

}  // namespace
}  // namespace eqmesh

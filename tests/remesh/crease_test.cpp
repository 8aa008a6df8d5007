// Crease chains of the input and remesh edges that follow them.
#include <gtest/gtest.h>

#include <cmath>

#include "hard_shapes.h"
#include "remesh/crease_curves.h"
#include "remesh/piercing.h"
#include "remesh/quality_checks.h"
#include "remesh/remesh.h"
#include "remesh_checks.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// The input vertex nearest to p.
uint32_t VertexAt(const Mesh& mesh, const Vec3& p) {
  uint32_t best = 0;
  for (uint32_t v = 1; v < mesh.positions.size(); ++v) {
    if ((mesh.positions[v] - p).squaredNorm() < (mesh.positions[best] - p).squaredNorm()) best = v;
  }
  return best;
}

CreasePlace AtInputVertex(uint32_t v) {
  CreasePlace place;
  place.input_vertex = v;
  return place;
}

TEST(CreaseCurves, ABoxHasTwelveChainsBetweenItsCorners) {
  const Mesh box = testing::MakeGridBox(1.0, 0.5, 0.25, 8);
  const CreaseCurves creases(box);
  ASSERT_EQ(creases.chains().size(), 12u);
  double total = 0.0;
  for (const CreaseChain& c : creases.chains()) {
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(c.faces.size() + 1, c.vertices.size());
    total += c.Length();
  }
  EXPECT_NEAR(total, 4.0 * (1.0 + 0.5 + 0.25), 1e-9);
  EXPECT_EQ(creases.SitesOf(VertexAt(box, Vec3(0, 0, 0))).size(), 3u);  // a corner
  EXPECT_EQ(creases.SitesOf(VertexAt(box, Vec3(0.5, 0, 0))).size(), 1u);
  EXPECT_TRUE(creases.SitesOf(VertexAt(box, Vec3(0.5, 0.25, 0))).empty());  // inside a side
}

TEST(CreaseCurves, SmoothShapesHaveNone) {
  EXPECT_TRUE(CreaseCurves(testing::MakeIcosphere(3)).empty());
  EXPECT_TRUE(CreaseCurves(testing::MakeTorus(48, 16)).empty());
}

TEST(CreaseCurves, ACylindersRimsAreClosedLoops) {
  const Mesh cylinder = testing::MakeCappedCylinder(1.0, 2.0, 24, 5);
  const CreaseCurves creases(cylinder);
  ASSERT_EQ(creases.chains().size(), 2u);
  for (const CreaseChain& c : creases.chains()) {
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.vertices.front(), c.vertices.back());
    EXPECT_EQ(c.vertices.size(), 25u);
  }
}

TEST(CreaseCurves, AnEdgeAlongAChainSplitsAtItsArcMidpoint) {
  const Mesh box = testing::MakeGridBox(1.0, 0.5, 0.25, 8);
  const CreaseCurves creases(box);
  const uint32_t a = VertexAt(box, Vec3(0, 0, 0)), b = VertexAt(box, Vec3(1, 0, 0));
  const std::optional<CreaseSite> site =
      creases.SplitSite(AtInputVertex(a), box.positions[a], AtInputVertex(b), box.positions[b]);
  ASSERT_TRUE(site.has_value());
  uint32_t face = kNoFace;
  const Vec3 p = creases.PositionAt(*site, box, &face);
  EXPECT_LT((p - Vec3(0.5, 0, 0)).norm(), 1e-12);
  ASSERT_NE(face, kNoFace);
  // The point lies on the face it names.
  const Face& f = box.faces[face];
  const Vec3 n = (box.positions[f[1]] - box.positions[f[0]]).cross(box.positions[f[2]] - box.positions[f[0]]);
  EXPECT_NEAR(n.normalized().dot(p - box.positions[f[0]]), 0.0, 1e-12);
  // A site placed there splits again with either end.
  CreasePlace mid;
  mid.site = *site;
  const std::optional<CreaseSite> quarter = creases.SplitSite(AtInputVertex(a), box.positions[a], mid, p);
  ASSERT_TRUE(quarter.has_value());
  EXPECT_LT((creases.PositionAt(*quarter, box, &face) - Vec3(0.25, 0, 0)).norm(), 1e-12);
}

TEST(CreaseCurves, EdgesAcrossASideOrTheLongWayRoundDoNotFollowAChain) {
  const Mesh box = testing::MakeGridBox(1.0, 0.5, 0.25, 8);
  const CreaseCurves creases(box);
  const uint32_t a = VertexAt(box, Vec3(0, 0, 0)), c = VertexAt(box, Vec3(1, 0.5, 0));
  EXPECT_FALSE(creases.SplitSite(AtInputVertex(a), box.positions[a], AtInputVertex(c), box.positions[c]));
  // Two points of a loop a quarter turn apart: the short arc, never the long one.
  const Mesh cylinder = testing::MakeCappedCylinder(1.0, 2.0, 24, 5);
  const CreaseCurves rims(cylinder);
  const uint32_t p = VertexAt(cylinder, Vec3(1, 0, 0)), q = VertexAt(cylinder, Vec3(0, 1, 0));
  EXPECT_FALSE(rims.SplitSite(AtInputVertex(p), cylinder.positions[p], AtInputVertex(q), cylinder.positions[q]));
  const uint32_t r = VertexAt(cylinder, Vec3(std::cos(M_PI / 6), std::sin(M_PI / 6), 0));
  const std::optional<CreaseSite> site =
      rims.SplitSite(AtInputVertex(p), cylinder.positions[p], AtInputVertex(r), cylinder.positions[r]);
  ASSERT_TRUE(site.has_value());
  uint32_t face = kNoFace;
  const Vec3 m = rims.PositionAt(*site, cylinder, &face);
  EXPECT_NEAR(std::atan2(m.y(), m.x()), M_PI / 12, 1e-9);  // on the rim polygon, halfway round the arc
}

// Piercing along the butterfly normal cuts a box's creases at every level; its
// edges followed, the remesh is the box.
TEST(RemeshCreases, ABoxRemeshesExactlyAndItsCreaseVerticesLieOnItsEdges) {
  const Mesh box = testing::MakeGridBox(1.0, 0.6, 0.4, 10);
  RemeshOptions options;
  options.levels = 4;
  RemeshReport report;
  const StatusOr<SemiRegularMesh> remesh = Remesh(box, options, &report);
  ASSERT_TRUE(remesh.ok()) << remesh.status().ToString();
  const Mesh finest = ExtractLevel(*remesh, 4);
  EXPECT_LT(testing::MaxVertexDistance(finest, box), 1e-9);  // the remesh lies on the box ...
  EXPECT_LT(testing::MaxVertexDistance(box, finest), 1e-9);  // ... and the box on the remesh
  EXPECT_EQ(testing::CountFlips(finest, box).flipped, 0u);
  size_t on_edges = 0;
  for (const Vec3& p : finest.positions) {
    const int at_bound = (std::abs(p.x()) < 1e-12 || std::abs(p.x() - 1.0) < 1e-12) +
                         (std::abs(p.y()) < 1e-12 || std::abs(p.y() - 0.6) < 1e-12) +
                         (std::abs(p.z()) < 1e-12 || std::abs(p.z() - 0.4) < 1e-12);
    on_edges += at_bound >= 2;
  }
  // 12 edges of 16 segments each at level 4 on a base of the 8 corners.
  EXPECT_EQ(report.base_vertices, 8u);
  EXPECT_EQ(on_edges, 8u + 12u * 15u);
}

}  // namespace
}  // namespace eqmesh

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "mesh/adaptive_level.h"
#include "metrics/surface_distance.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// A semi-regular mesh over `base` refined `levels` times, every new vertex on the
// edge midpoint plus a bump near (0.7, 0, 0.7): flat almost everywhere, detailed
// in one place, so an adaptive cut has somewhere to spend its triangles.
SemiRegularMesh Bumpy(const Mesh& base, int levels, bool on_sphere) {
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()), base.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  SemiRegularMesh m;
  m.hierarchy = std::move(h).value();
  m.positions = base.positions;
  auto bump = [](const Vec3& p) { return 0.25 * std::exp(-(p - Vec3(0.7, 0.0, 0.7)).squaredNorm() / 0.03); };
  for (int j = 0; j < levels; ++j) {
    for (uint32_t k = 0; k < m.hierarchy.NumOddVertices(j); ++k) {
      const Edge& e = m.hierarchy.OddEdge(j, k);
      Vec3 p = 0.5 * (m.positions[e[0]] + m.positions[e[1]]);
      if (on_sphere) p.normalize();
      m.positions.push_back(p);
    }
  }
  for (Vec3& p : m.positions) p += bump(p) * (on_sphere ? p.normalized() : Vec3::UnitZ());
  return m;
}

// Directed edge -> uses.
std::map<std::pair<uint32_t, uint32_t>, int> DirectedEdges(const Mesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (const Face& f : m.faces) {
    for (int c = 0; c < 3; ++c) ++edges[{f[c], f[(c + 1) % 3]}];
  }
  return edges;
}

TEST(AdaptiveLevel, ClosedSurfaceStaysClosedAndOrientedWithinEveryBudget) {
  const SemiRegularMesh m = Bumpy(testing::MakeIcosphere(0), 5, true);
  for (uint64_t budget : {20u, 45u, 200u, 1000u, 5000u, 20479u}) {
    AdaptiveLevelReport report;
    const Mesh cut = ExtractAdaptiveLevel(m, budget, &report);
    EXPECT_LE(cut.faces.size(), budget);
    EXPECT_GE(cut.faces.size(), budget - budget / 10 - 4) << "budget left unspent";
    EXPECT_TRUE(report.within_budget);
    const auto edges = DirectedEdges(cut);
    for (const auto& [edge, uses] : edges) {
      ASSERT_EQ(uses, 1) << "budget " << budget;
      const auto twin = edges.count({edge.second, edge.first});
      ASSERT_EQ(twin, 1u) << "budget " << budget << ": a crack or T-junction at edge " << edge.first << "-"
                          << edge.second;
    }
  }
}

TEST(AdaptiveLevel, OpenSurfaceGainsNoBoundaryInside) {
  const SemiRegularMesh m = Bumpy(testing::MakeDisc(2), 4, false);
  const Mesh finest = ExtractLevel(m, m.hierarchy.levels());
  std::set<std::pair<double, double>> rim;  // boundary vertices of the uniform finest level
  const auto finest_edges = DirectedEdges(finest);
  for (const auto& [edge, uses] : finest_edges) {
    if (finest_edges.count({edge.second, edge.first}) == 0) {
      rim.insert({finest.positions[edge.first].x(), finest.positions[edge.first].y()});
    }
  }
  for (uint64_t budget : {100u, 400u, 1500u}) {
    const Mesh cut = ExtractAdaptiveLevel(m, budget);
    EXPECT_LE(cut.faces.size(), budget);
    const auto edges = DirectedEdges(cut);
    for (const auto& [edge, uses] : edges) {
      ASSERT_EQ(uses, 1);
      if (edges.count({edge.second, edge.first}) != 0) continue;
      const Vec3& a = cut.positions[edge.first];
      EXPECT_EQ(rim.count({a.x(), a.y()}), 1u) << "budget " << budget << ": a boundary edge inside the disc";
    }
  }
}

TEST(AdaptiveLevel, SpendsTheBudgetWhereTheSurfaceNeedsIt) {
  const SemiRegularMesh m = Bumpy(testing::MakeDisc(2), 5, false);  // flat but for the bump
  const Mesh finest = ExtractLevel(m, 5);
  const Mesh uniform = ExtractLevel(m, 3);
  AdaptiveLevelReport report;
  const Mesh cut = ExtractAdaptiveLevel(m, uniform.faces.size(), &report);
  EXPECT_LE(cut.faces.size(), uniform.faces.size());
  EXPECT_EQ(report.finest_level, 5);  // the bump gets the finest faces
  CompareOptions options;
  options.samples = 50000;  // ample for a 6 dB margin
  auto adaptive_error = CompareSurfaces(finest, cut, options);
  auto uniform_error = CompareSurfaces(finest, uniform, options);
  ASSERT_TRUE(adaptive_error.ok() && uniform_error.ok());
  EXPECT_GT(adaptive_error->psnr_db, uniform_error->psnr_db + 6.0)
      << adaptive_error->psnr_db << " dB against " << uniform_error->psnr_db;
}

TEST(AdaptiveLevel, IsDeterministicAndExactAtTheEnds) {
  const SemiRegularMesh m = Bumpy(testing::MakeIcosphere(0), 4, true);
  const Mesh a = ExtractAdaptiveLevel(m, 700), b = ExtractAdaptiveLevel(m, 700);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.faces, b.faces);
  const Mesh all = ExtractAdaptiveLevel(m, 1u << 20);
  EXPECT_EQ(all.faces, ExtractLevel(m, 4).faces);
  AdaptiveLevelReport report;
  const Mesh base = ExtractAdaptiveLevel(m, 10, &report);  // fewer than the base's 20
  EXPECT_EQ(base.faces, ExtractLevel(m, 0).faces);
  EXPECT_FALSE(report.within_budget);
}

TEST(AdaptiveLevel, FlatRegionsAreNotRefined) {
  Mesh plane = testing::MakeDisc(2);
  SemiRegularMesh m = Bumpy(plane, 4, false);
  for (Vec3& p : m.positions) p.z() = 0.0;  // no detail anywhere: splitting buys nothing
  const Mesh cut = ExtractAdaptiveLevel(m, 100000);
  EXPECT_EQ(cut.faces.size(), ExtractLevel(m, 4).faces.size());  // within budget: the full level
  const Mesh tight = ExtractAdaptiveLevel(m, ExtractLevel(m, 4).faces.size() - 1);
  EXPECT_EQ(tight.faces.size(), ExtractLevel(m, 0).faces.size());
}

}  // namespace
}  // namespace eqmesh

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "test_support.h"
#include "wavelet/butterfly.h"

namespace eqmesh {
namespace {

SemiRegularHierarchy Build(const Mesh& m, int levels) {
  uint32_t n = static_cast<uint32_t>(m.positions.size());
  for (const Face& f : m.faces)
    for (uint32_t v : f) n = std::max(n, v + 1);
  auto h = SemiRegularHierarchy::Build(n, m.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  return std::move(h).value();
}

std::map<uint32_t, double> StencilOf(const StencilTable& t, uint32_t k) {
  std::map<uint32_t, double> out;
  for (uint32_t i = t.offsets[k]; i < t.offsets[k + 1]; ++i) out[t.indices[i]] += t.weights[i];
  return out;
}

void ExpectWeightsSumToOne(const SemiRegularHierarchy& h) {
  for (int j = 0; j < h.levels(); ++j) {
    const StencilTable t = BuildButterflyStencils(h, j);
    ASSERT_EQ(t.size(), h.NumOddVertices(j));
    for (uint32_t k = 0; k < t.size(); ++k) {
      double sum = 0.0;
      for (uint32_t i = t.offsets[k]; i < t.offsets[k + 1]; ++i) {
        sum += t.weights[i];
        EXPECT_LT(t.indices[i], h.NumVertices(j));
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "level " << j << " odd " << k;
    }
  }
}

TEST(Butterfly, WeightsSumToOne) {
  ExpectWeightsSumToOne(Build(testing::MakeIcosphere(0), 3));
  ExpectWeightsSumToOne(Build(testing::MakeTorus(8, 6), 2));
  ExpectWeightsSumToOne(Build(testing::MakeDisc(2), 3));
  ExpectWeightsSumToOne(Build(Mesh{{}, {{0, 1, 2}}}, 3));
}

TEST(Butterfly, ExtraordinaryWeightsSumToOneQuarterAndAreSymmetric) {
  for (uint32_t k = 3; k <= 12; ++k) {
    const std::vector<double> s = ButterflyExtraordinaryWeights(k);
    ASSERT_EQ(s.size(), k);
    double sum = 0.0;
    for (double w : s) sum += w;
    EXPECT_NEAR(sum, 0.25, 1e-15) << k;
    for (uint32_t i = 1; i < k; ++i) EXPECT_NEAR(s[i], s[k - i], 1e-15);
  }
  EXPECT_TRUE(ButterflyExtraordinaryWeights(2).empty());
}

TEST(Butterfly, RegularPatchUsesEightPointRule) {
  // Every torus vertex has valence 6.
  const Mesh torus = testing::MakeTorus(8, 6);
  const SemiRegularHierarchy h = Build(torus, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  for (uint32_t k = 0; k < t.size(); ++k) {
    const auto s = StencilOf(t, k);
    ASSERT_EQ(s.size(), 8u);
    const Edge& e = h.OddEdge(0, k);
    EXPECT_DOUBLE_EQ(s.at(e[0]), 0.5);
    EXPECT_DOUBLE_EQ(s.at(e[1]), 0.5);
    int eighths = 0, sixteenths = 0;
    for (const auto& [v, w] : s) {
      eighths += w == 0.125;
      sixteenths += w == -0.0625;
    }
    EXPECT_EQ(eighths, 2);
    EXPECT_EQ(sixteenths, 4);
  }
}

// Closed bipyramid: apexes 0 (top) and 1 (bottom) of valence k, equator 2..k+1.
Mesh MakeBipyramid(uint32_t k) {
  Mesh m;
  m.positions = {{0, 0, 1}, {0, 0, -1}};
  for (uint32_t i = 0; i < k; ++i) {
    const double a = 2.0 * M_PI * i / k;
    m.positions.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  for (uint32_t i = 0; i < k; ++i) {
    const uint32_t p = 2 + i, q = 2 + (i + 1) % k;
    m.faces.push_back({0, p, q});
    m.faces.push_back({1, q, p});
  }
  return m;
}

class ExtraordinaryRule : public ::testing::TestWithParam<uint32_t> {};

TEST_P(ExtraordinaryRule, MatchesZorinWeights) {
  const uint32_t k = GetParam();
  const SemiRegularHierarchy h = Build(MakeBipyramid(k), 2);
  // Level 1: the top apex keeps valence k; its neighbours are odd vertices of
  // valence 6, so only the apex's rule applies. Ring order = angle around z.
  std::vector<double> angle(h.NumVertices(1));
  std::vector<Vec3> pos(h.NumVertices(1));
  const Mesh base = MakeBipyramid(k);
  for (uint32_t v = 0; v < base.positions.size(); ++v) pos[v] = base.positions[v];
  for (uint32_t o = 0; o < h.NumOddVertices(0); ++o) {
    const Edge& e = h.OddEdge(0, o);
    pos[h.NumVertices(0) + o] = 0.5 * (pos[e[0]] + pos[e[1]]);
  }
  const StencilTable t = BuildButterflyStencils(h, 1);
  const std::vector<double> s = ButterflyExtraordinaryWeights(k);
  int checked = 0;
  for (uint32_t o = 0; o < t.size(); ++o) {
    const Edge& e = h.OddEdge(1, o);
    if (e[0] != 0 && e[1] != 0) continue;
    const uint32_t other = e[0] == 0 ? e[1] : e[0];
    const auto st = StencilOf(t, o);
    EXPECT_DOUBLE_EQ(st.at(0), 0.75);
    const double a0 = std::atan2(pos[other].y(), pos[other].x());
    size_t nonzero = 1;
    for (uint32_t i = 0; i < k; ++i) {
      // Ring neighbour at angle a0 + 2πi/k: the odd vertex on apex edge.
      const double a = a0 + 2.0 * M_PI * i / k;
      uint32_t found = ~0u;
      for (uint32_t v = h.NumVertices(0); v < h.NumVertices(1); ++v) {
        if (std::abs(pos[v].z() - 0.5) < 1e-12 &&
            std::abs(pos[v].x() - 0.5 * std::cos(a)) < 1e-9 &&
            std::abs(pos[v].y() - 0.5 * std::sin(a)) < 1e-9)
          found = v;
      }
      ASSERT_NE(found, ~0u);
      const auto it = st.find(found);
      const double w = it == st.end() ? 0.0 : it->second;
      EXPECT_NEAR(w, s[i], 1e-15) << "k=" << k << " i=" << i;
      nonzero += s[i] != 0.0;
    }
    EXPECT_EQ(st.size(), nonzero);
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(k));
}

INSTANTIATE_TEST_SUITE_P(Valences, ExtraordinaryRule, ::testing::Values(3u, 4u, 5u, 7u, 9u));

TEST(Butterfly, ExtraordinaryFormulaValues) {
  const auto s5 = ButterflyExtraordinaryWeights(5);
  for (uint32_t i = 0; i < 5; ++i) {
    const double a = 2.0 * M_PI * i / 5;
    EXPECT_NEAR(s5[i], (0.25 + std::cos(a) + 0.5 * std::cos(2 * a)) / 5, 1e-15);
  }
  EXPECT_NEAR(s5[0], 0.35, 1e-15);
  const auto s4 = ButterflyExtraordinaryWeights(4);
  EXPECT_EQ(s4, (std::vector<double>{0.375, 0.0, -0.125, 0.0}));
}

TEST(Butterfly, BothEndpointsExtraordinaryAverages) {
  // Icosahedron: every vertex has valence 5.
  const SemiRegularHierarchy h = Build(testing::MakeIcosphere(0), 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  for (uint32_t k = 0; k < t.size(); ++k) {
    const auto s = StencilOf(t, k);
    const Edge& e = h.OddEdge(0, k);
    // 3/8 centre + 1/2 * s_0 from the other side's rule.
    EXPECT_NEAR(s.at(e[0]), 0.375 + 0.5 * 0.35, 1e-15);
    EXPECT_NEAR(s.at(e[1]), 0.375 + 0.5 * 0.35, 1e-15);
  }
}

TEST(Butterfly, BoundaryEdgesUseFourPointRule) {
  const Mesh disc = testing::MakeDisc(2);
  const SemiRegularHierarchy h = Build(disc, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  const uint32_t outer_first = 7, outer_count = 12;  // ring 2 of MakeDisc
  auto on_outer = [&](uint32_t v) { return v >= outer_first; };
  int checked = 0;
  for (uint32_t k = 0; k < t.size(); ++k) {
    const Edge& e = h.OddEdge(0, k);
    if (!on_outer(e[0]) || !on_outer(e[1])) continue;
    const auto s = StencilOf(t, k);
    ASSERT_EQ(s.size(), 4u);
    EXPECT_DOUBLE_EQ(s.at(e[0]), 9.0 / 16);
    EXPECT_DOUBLE_EQ(s.at(e[1]), 9.0 / 16);
    for (const auto& [v, w] : s) {
      if (v == e[0] || v == e[1]) continue;
      EXPECT_DOUBLE_EQ(w, -1.0 / 16);
      ASSERT_TRUE(on_outer(v));
      // The outer neighbours sit one step beyond the edge along the ring.
      const uint32_t i = v - outer_first, a = e[0] - outer_first, b = e[1] - outer_first;
      const bool beyond_a = (i + 1) % outer_count == a || (a + 1) % outer_count == i;
      const bool beyond_b = (i + 1) % outer_count == b || (b + 1) % outer_count == i;
      EXPECT_TRUE(beyond_a != beyond_b);
    }
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(outer_count));
}

TEST(Butterfly, TriangleLoopMergesCoincidentNeighbours) {
  const SemiRegularHierarchy h = Build(Mesh{{}, {{0, 1, 2}}}, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  for (uint32_t k = 0; k < 3; ++k) {
    const auto s = StencilOf(t, k);
    const Edge& e = h.OddEdge(0, k);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_DOUBLE_EQ(s.at(e[0]), 9.0 / 16);
    EXPECT_DOUBLE_EQ(s.at(e[1]), 9.0 / 16);
    EXPECT_DOUBLE_EQ(s.at(3 - e[0] - e[1]), -1.0 / 8);
  }
}

TEST(Butterfly, NonManifoldInputFallsBackWithoutCrashing) {
  // Three faces on edge (0,1), a bowtie at vertex 0, and a flipped face.
  const std::vector<Face> faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {0, 5, 6},
                                   {0, 6, 7}, {7, 8, 9}, {7, 9, 8}};
  auto h = SemiRegularHierarchy::Build(10, faces, 2);
  ASSERT_TRUE(h.ok());
  ExpectWeightsSumToOne(*h);
  const StencilTable t = BuildButterflyStencils(*h, 0);
  const auto s = StencilOf(t, 0);  // edge (0,1)
  EXPECT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s.at(0), 0.5);
}

TEST(Butterfly, PlanarMeshStaysPlanar) {
  Mesh disc = testing::MakeDisc(3);
  uint32_t seed = 7;
  for (Vec3& p : disc.positions) {
    seed = seed * 1664525u + 1013904223u;
    p.x() += 0.01 * (static_cast<double>(seed >> 8) / (1u << 24) - 0.5);
  }
  const SemiRegularHierarchy h = Build(disc, 1);
  std::vector<Vec3> out;
  ApplyStencils(BuildButterflyStencils(h, 0), disc.positions, &out);
  for (const Vec3& p : out) EXPECT_EQ(p.z(), 0.0);
}

TEST(Butterfly, ReproducesLinearFunctionsOnRegularGrid) {
  // Affine maps commute with affine-invariant stencils on any mesh.
  const Mesh torus = testing::MakeTorus(10, 8);
  const SemiRegularHierarchy h = Build(torus, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  Eigen::Matrix3d a;
  a << 1, 2, 0, -1, 0.5, 3, 0.25, 0, 1;
  const Vec3 shift(0.3, -2, 5);
  std::vector<Vec3> mapped;
  for (const Vec3& p : torus.positions) mapped.push_back(a * p + shift);
  std::vector<Vec3> p0, p1;
  ApplyStencils(t, torus.positions, &p0);
  ApplyStencils(t, mapped, &p1);
  for (size_t k = 0; k < p0.size(); ++k) EXPECT_LT((a * p0[k] + shift - p1[k]).norm(), 1e-12);
}

// n x n lattice of unit squares split along one diagonal: interior vertices have
// valence 6, and edges near the border need ghost wings.
Mesh MakeGrid(uint32_t n) {
  Mesh m;
  for (uint32_t y = 0; y <= n; ++y)
    for (uint32_t x = 0; x <= n; ++x) m.positions.emplace_back(x + 0.5 * y, 0.8 * y, 0.0);
  auto id = [n](uint32_t x, uint32_t y) { return y * (n + 1) + x; };
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      m.faces.push_back({id(x, y), id(x + 1, y), id(x, y + 1)});
      m.faces.push_back({id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  return m;
}

TEST(Butterfly, GhostWingsKeepLinearPrecisionNearTheBoundary) {
  const Mesh grid = MakeGrid(5);
  const SemiRegularHierarchy h = Build(grid, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  std::vector<Vec3> predicted;
  ApplyStencils(t, grid.positions, &predicted);
  std::map<std::pair<uint32_t, uint32_t>, int> faces_on_edge;
  for (const Face& f : grid.faces)
    for (int i = 0; i < 3; ++i)
      faces_on_edge[std::minmax(f[i], f[(i + 1) % 3])]++;
  int ghosts = 0, interior = 0;
  for (uint32_t k = 0; k < t.size(); ++k) {
    const Edge& e = h.OddEdge(0, k);
    if (faces_on_edge[std::minmax(e[0], e[1])] != 2) continue;  // 4-point rule, inexact at corners
    ++interior;
    const Vec3 mid = 0.5 * (grid.positions[e[0]] + grid.positions[e[1]]);
    EXPECT_LT((predicted[k] - mid).norm(), 1e-14) << k;
    // Ghosts fold into the weights of vertices already in the stencil.
    bool plain = true;
    for (const auto& [v, w] : StencilOf(t, k)) plain = plain && (w == 0.5 || w == 0.125 || w == -0.0625);
    ghosts += !plain;
  }
  EXPECT_GT(interior, 0);
  EXPECT_GT(ghosts, 0);
}

TEST(Butterfly, FramesAreOrthonormalAndFollowTheSurface) {
  const Mesh sphere = testing::MakeIcosphere(1);
  const SemiRegularHierarchy h = Build(sphere, 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  std::vector<Vec3> predicted;
  ApplyStencils(t, sphere.positions, &predicted);
  const auto frames = ComputeOddFrames(h, 0, t, sphere.positions);
  ASSERT_EQ(frames.size(), t.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    const LocalFrame& f = frames[k];
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.tangent.norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.bitangent.norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.normal.dot(f.tangent), 0.0, 1e-12);
    EXPECT_NEAR(f.normal.dot(f.bitangent), 0.0, 1e-12);
    EXPECT_NEAR(f.tangent.dot(f.bitangent), 0.0, 1e-12);
    EXPECT_GT(f.normal.dot(predicted[k].normalized()), 0.99);  // outward
    const Edge& e = h.OddEdge(0, static_cast<uint32_t>(k));
    EXPECT_GT(f.tangent.dot((sphere.positions[e[1]] - sphere.positions[e[0]]).normalized()), 0.99);
  }
}

TEST(Butterfly, DegenerateGeometryGivesValidFrames) {
  const SemiRegularHierarchy h = Build(testing::MakeIcosphere(0), 1);
  const StencilTable t = BuildButterflyStencils(h, 0);
  const std::vector<Vec3> collapsed(h.NumVertices(0), Vec3(1, 2, 3));
  for (const LocalFrame& f : ComputeOddFrames(h, 0, t, collapsed)) {
    EXPECT_EQ(f.normal, Vec3::UnitZ());
    EXPECT_EQ(f.tangent, Vec3::UnitX());
    EXPECT_EQ(f.bitangent, Vec3::UnitY());
  }
}

// The decoder builds stencils and frames one odd vertex at a time; they must be
// the table's, bit for bit, on regular, extraordinary, boundary, non-manifold
// and degenerate levels.
TEST(Butterfly, OnDemandStencilsAndFramesMatchTheTableBitForBit) {
  Mesh fin = testing::MakeDisc(1);
  fin.faces.push_back({0, 1, static_cast<uint32_t>(fin.positions.size())});  // a third face on edge (0, 1)
  fin.positions.push_back(Vec3(0.1, 0.2, 0.9));
  std::vector<std::pair<Mesh, int>> cases = {{testing::MakeIcosphere(0), 3}, {testing::MakeTorus(6, 5), 2},
                                             {testing::MakeDisc(2), 2}, {fin, 2}};
  Mesh flat = testing::MakeIcosphere(0);
  for (Vec3& p : flat.positions) p = Vec3(1, 2, 3);
  cases.push_back({flat, 1});
  for (const auto& [mesh, levels] : cases) {
    const SemiRegularHierarchy h = Build(mesh, levels);
    std::vector<Vec3> positions = mesh.positions;
    positions.resize(h.NumVertices(0), Vec3::Zero());
    for (int j = 0; j < levels; ++j) {
      const StencilTable table = BuildButterflyStencils(h, j);
      std::vector<Vec3> from_table;
      ApplyStencils(table, positions, &from_table);
      const std::vector<LocalFrame> frames = ComputeOddFrames(h, j, table, positions);
      const ButterflyPredictor predictor(h, j);
      const OddFrames on_demand(predictor, positions);
      for (uint32_t k = 0; k < h.NumOddVertices(j); ++k) {
        ASSERT_EQ(predictor.Stencil(k).Apply(positions), from_table[k]) << "level " << j << " odd " << k;
        const LocalFrame f = on_demand.Frame(k);
        ASSERT_EQ(f.normal, frames[k].normal) << "level " << j << " odd " << k;
        ASSERT_EQ(f.tangent, frames[k].tangent);
        ASSERT_EQ(f.bitangent, frames[k].bitangent);
      }
      positions.insert(positions.end(), from_table.begin(), from_table.end());
    }
  }
}

}  // namespace
}  // namespace eqmesh

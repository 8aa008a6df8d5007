#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "test_support.h"
#include "wavelet/local_frame.h"
#include "wavelet/transform.h"

namespace eqmesh {
namespace {

constexpr WaveletKind kKinds[] = {WaveletKind::kUnlifted, WaveletKind::kLifted};

SemiRegularHierarchy Build(const Mesh& m, int levels) {
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(m.positions.size()), m.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  return std::move(h).value();
}

double Diagonal(const std::vector<Vec3>& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

double MaxDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

// Semi-regular positions: butterfly refinement of the base plus random details
// of relative size `amplitude` halving per level.
std::vector<Vec3> RefineWithNoise(const SemiRegularHierarchy& h, std::vector<Vec3> positions,
                                  double amplitude, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < h.levels(); ++j) {
    const RefinementStep step(h, j, WaveletKind::kUnlifted);
    std::vector<Vec3> details(step.num_odd());
    for (Vec3& d : details) d = amplitude * Vec3(u(rng), u(rng), u(rng));
    std::vector<Vec3> fine;
    step.Synthesize(positions, details, &fine);
    positions = std::move(fine);
    amplitude *= 0.5;
  }
  return positions;
}

void ExpectRoundTrip(const Mesh& base, int levels) {
  const SemiRegularHierarchy h = Build(base, levels);
  const std::vector<Vec3> finest = RefineWithNoise(h, base.positions, 0.05, 11);
  ASSERT_EQ(finest.size(), h.NumVertices(levels));
  const double tolerance = 1e-9 * Diagonal(finest);
  for (WaveletKind kind : kKinds) {
    const WaveletCoefficients c = ForwardTransform(h, finest, kind);
    ASSERT_EQ(c.scaling.size(), h.NumVertices(0));
    ASSERT_EQ(c.details.size(), static_cast<size_t>(levels));
    EXPECT_LT(MaxDistance(InverseTransform(h, c, kind, levels), finest), tolerance)
        << "kind " << static_cast<int>(kind);
  }
}

TEST(WaveletTransform, RoundTripIcosphere) {
  Mesh ico = testing::MakeIcosphere(0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (Vec3& p : ico.positions) p += Vec3(u(rng), u(rng), u(rng));
  ExpectRoundTrip(ico, 4);
}

TEST(WaveletTransform, RoundTripTorus) { ExpectRoundTrip(testing::MakeTorus(8, 6), 3); }

TEST(WaveletTransform, RoundTripDiscWithBoundary) { ExpectRoundTrip(testing::MakeDisc(2), 3); }

TEST(WaveletTransform, LiftedDiffersFromUnlifted) {
  const Mesh torus = testing::MakeTorus(8, 6);
  const SemiRegularHierarchy h = Build(torus, 2);
  const std::vector<Vec3> finest = RefineWithNoise(h, torus.positions, 0.05, 5);
  const WaveletCoefficients a = ForwardTransform(h, finest, WaveletKind::kUnlifted);
  const WaveletCoefficients b = ForwardTransform(h, finest, WaveletKind::kLifted);
  EXPECT_GT(MaxDistance(a.scaling, b.scaling), 1e-6);
}

TEST(WaveletTransform, PlanarCoarseMeshWithZeroDetailsStaysPlanar) {
  Mesh disc = testing::MakeDisc(3);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (Vec3& p : disc.positions) p += Vec3(u(rng), u(rng), 0.0);  // irregular but planar
  const SemiRegularHierarchy h = Build(disc, 3);
  for (WaveletKind kind : kKinds) {
    WaveletCoefficients c;
    c.scaling = disc.positions;
    for (int j = 0; j < 3; ++j) c.details.emplace_back(h.NumOddVertices(j), Vec3::Zero());
    const std::vector<Vec3> fine = InverseTransform(h, c, kind, 3);
    ASSERT_EQ(fine.size(), h.NumVertices(3));
    for (const Vec3& p : fine) EXPECT_EQ(p.z(), 0.0);
  }
}

TEST(WaveletTransform, PartialInverseGivesCoarserLevelForUnlifted) {
  const Mesh ico = testing::MakeIcosphere(0);
  const SemiRegularHierarchy h = Build(ico, 3);
  const std::vector<Vec3> finest = RefineWithNoise(h, ico.positions, 0.05, 21);
  const WaveletCoefficients c = ForwardTransform(h, finest, WaveletKind::kUnlifted);
  for (int level = 0; level <= 3; ++level) {
    const std::vector<Vec3> part = InverseTransform(h, c, WaveletKind::kUnlifted, level);
    ASSERT_EQ(part.size(), h.NumVertices(level));
    for (uint32_t v = 0; v < part.size(); ++v) {
      if (v < h.NumVertices(0)) {
        EXPECT_EQ(part[v], finest[v]);  // base vertices are copied, bit for bit
      } else {
        EXPECT_LT((part[v] - finest[v]).norm(), 1e-14);  // prediction + (x - prediction)
      }
    }
  }
  // Progressive decoding: later levels may be missing.
  WaveletCoefficients head = c;
  head.details.resize(1);
  EXPECT_EQ(InverseTransform(h, head, WaveletKind::kUnlifted, 1).size(), h.NumVertices(1));
  EXPECT_TRUE(InverseTransform(h, head, WaveletKind::kUnlifted, 2).empty());
}

TEST(WaveletTransform, RejectsMismatchedCoefficients) {
  const SemiRegularHierarchy h = Build(testing::MakeIcosphere(0), 2);
  WaveletCoefficients c;
  c.scaling.assign(11, Vec3::Zero());
  c.details = {std::vector<Vec3>(h.NumOddVertices(0)), std::vector<Vec3>(h.NumOddVertices(1))};
  EXPECT_FALSE(ValidateCoefficients(h, c, 2).ok());
  EXPECT_TRUE(InverseTransform(h, c, WaveletKind::kLifted, 2).empty());
  c.scaling.assign(12, Vec3::Zero());
  EXPECT_TRUE(ValidateCoefficients(h, c, 2).ok());
  c.details[1].pop_back();
  EXPECT_FALSE(ValidateCoefficients(h, c, 2).ok());
  EXPECT_TRUE(ValidateCoefficients(h, c, 1).ok());
  EXPECT_TRUE(ForwardTransform(h, std::vector<Vec3>(5), WaveletKind::kUnlifted).scaling.empty());
}

TEST(WaveletTransform, UpdateWeightsFollowFaceCounts) {
  // Icosahedron level 1: base vertices have valence 5, the others 6.
  const SemiRegularHierarchy h = Build(testing::MakeIcosphere(0), 2);
  const RefinementStep step(h, 1, WaveletKind::kLifted);
  const StencilTable& u = step.update();
  ASSERT_EQ(u.size(), h.NumVertices(1));
  for (uint32_t v = 0; v < u.size(); ++v) {
    const uint32_t k = u.offsets[v + 1] - u.offsets[v];
    EXPECT_EQ(k, v < 12 ? 5u : 6u);
    for (uint32_t i = u.offsets[v]; i < u.offsets[v + 1]; ++i) {
      EXPECT_DOUBLE_EQ(u.weights[i], 3.0 / (4.0 * k));
    }
  }
  // Boundary: a single triangle, F_v = 1, boundary odd vertices F_m = 3.
  const SemiRegularHierarchy tri = *SemiRegularHierarchy::Build(3, {{0, 1, 2}}, 1);
  const RefinementStep t(tri, 0, WaveletKind::kLifted);
  for (double w : t.update().weights) EXPECT_DOUBLE_EQ(w, 3.0 / 8.0);
  const RefinementStep unlifted(h, 1, WaveletKind::kUnlifted);
  EXPECT_TRUE(unlifted.update().weights.empty());
}

TEST(WaveletTransform, LiftedScalingValuesKeepTheMean) {
  // Zeroth moment (the point of the update): on a regular torus every fine vertex
  // has the same area and every coarse vertex four times that, so the coarse
  // scaling values must have the same mean as the fine mesh.
  const Mesh torus = testing::MakeTorus(8, 6);
  const SemiRegularHierarchy h = Build(torus, 1);
  const RefinementStep step(h, 0, WaveletKind::kLifted);
  std::vector<Vec3> fine;
  const std::vector<Vec3> constant(step.num_odd(), Vec3(0, 0, 1));
  step.Synthesize(torus.positions, constant, &fine);
  std::vector<Vec3> coarse, details;
  step.Analyze(fine, &coarse, &details);
  Vec3 fine_mean = Vec3::Zero(), coarse_mean = Vec3::Zero();
  for (const Vec3& p : fine) fine_mean += p / static_cast<double>(fine.size());
  for (const Vec3& p : coarse) coarse_mean += p / static_cast<double>(coarse.size());
  EXPECT_LT((fine_mean - coarse_mean).norm(), 1e-12);
}

TEST(WaveletTransform, FramesAreOrthonormalAndLocalRoundTrips) {
  const Mesh ico = testing::MakeIcosphere(0);
  const SemiRegularHierarchy h = Build(ico, 2);
  const std::vector<Vec3> finest = RefineWithNoise(h, ico.positions, 0.05, 2);
  for (WaveletKind kind : kKinds) {
    const WaveletCoefficients c = ForwardTransform(h, finest, kind);
    std::vector<Vec3> values = c.scaling;
    for (int j = 0; j < 2; ++j) {
      const RefinementStep step(h, j, kind);
      const std::vector<LocalFrame> frames = FramesForLevel(step, values);
      ASSERT_EQ(frames.size(), step.num_odd());
      for (size_t k = 0; k < frames.size(); ++k) {
        const LocalFrame& f = frames[k];
        Eigen::Matrix3d m;
        m << f.normal, f.tangent, f.bitangent;
        EXPECT_LT((m.transpose() * m - Eigen::Matrix3d::Identity()).norm(), 1e-12);
        EXPECT_NEAR(m.determinant(), 1.0, 1e-12);  // right-handed
        const Vec3& d = c.details[j][k];
        EXPECT_LT((FromLocal(f, ToLocal(f, d)) - d).norm(), 1e-15 + 1e-12 * d.norm());
      }
      std::vector<Vec3> fine;
      step.Synthesize(values, c.details[j], &fine);
      values = std::move(fine);
    }
  }
}

TEST(WaveletTransform, NormalMeshHasNoTangentialDetails) {
  const Mesh ico = testing::MakeIcosphere(0);
  const int levels = 3;
  const SemiRegularHierarchy h = Build(ico, levels);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  std::vector<Vec3> positions = ico.positions;
  for (int j = 0; j < levels; ++j) {
    const RefinementStep step(h, j, WaveletKind::kUnlifted);
    const std::vector<LocalFrame> frames = FramesForLevel(step, positions);
    std::vector<Vec3> details(step.num_odd());
    for (size_t k = 0; k < details.size(); ++k) details[k] = u(rng) * frames[k].normal;
    std::vector<Vec3> fine;
    step.Synthesize(positions, details, &fine);
    positions = std::move(fine);
  }
  const WaveletCoefficients c = ForwardTransform(h, positions, WaveletKind::kUnlifted);
  std::vector<Vec3> values = c.scaling;
  for (int j = 0; j < levels; ++j) {
    const RefinementStep step(h, j, WaveletKind::kUnlifted);
    const std::vector<LocalFrame> frames = FramesForLevel(step, values);
    for (size_t k = 0; k < frames.size(); ++k) {
      const Vec3 local = ToLocal(frames[k], c.details[j][k]);
      EXPECT_LT(std::abs(local.y()), 1e-12);
      EXPECT_LT(std::abs(local.z()), 1e-12);
    }
    std::vector<Vec3> fine;
    step.Synthesize(values, c.details[j], &fine);
    values = std::move(fine);
  }
}

// The decoder's synthesis builds each stencil as it applies it and takes empty
// details for all-zero ones; both must give the table's bits exactly.
TEST(WaveletTransform, SynthesisWithoutATableOrDetailsMatchesTheTableBitForBit) {
  for (const Mesh& base : {testing::MakeIcosphere(0), testing::MakeDisc(2)}) {
    const SemiRegularHierarchy h = Build(base, 2);
    const std::vector<Vec3> finest = RefineWithNoise(h, base.positions, 0.05, 3);
    for (WaveletKind kind : kKinds) {
      const WaveletCoefficients c = ForwardTransform(h, finest, kind);
      std::vector<Vec3> coarse = c.scaling;
      for (int j = 0; j < h.levels(); ++j) {
        const RefinementStep with_table(h, j, kind);
        with_table.stencils();
        const RefinementStep on_demand(h, j, kind);
        std::vector<Vec3> a, b;
        with_table.Synthesize(coarse, c.details[j], &a);
        on_demand.Synthesize(coarse, c.details[j], &b);
        ASSERT_EQ(a, b) << "level " << j;
        const std::vector<Vec3> zero(on_demand.num_odd(), Vec3::Zero());
        std::vector<Vec3> z_table, z_empty;
        with_table.Synthesize(coarse, zero, &z_table);
        on_demand.Synthesize(coarse, {}, &z_empty);
        ASSERT_EQ(z_table, z_empty) << "level " << j;
        coarse = std::move(a);
      }
    }
  }
}

}  // namespace
}  // namespace eqmesh

// BaseInfluenceWeights refines each base vertex's impulse only where it reaches
// (lib/coding/base_influence.cpp); it must give exactly the doubles of refining
// the impulse over the whole mesh, closed or with a boundary.
#include <gtest/gtest.h>

#include <vector>

#include "codec/codec_fixtures.h"
#include "coding/base_influence.h"
#include "test_support.h"
#include "wavelet/butterfly.h"

namespace eqmesh::testing {
namespace {

// The dense refinement: every stencil of every level for every impulse.
std::vector<double> DenseInfluenceWeights(const SemiRegularHierarchy& hierarchy) {
  const uint32_t base = hierarchy.NumVertices(0);
  std::vector<double> weights(base);
  for (uint32_t i = 0; i < base; ++i) {
    std::vector<double> values(base, 0.0);
    values[i] = 1.0;
    for (int j = 0; j < hierarchy.levels(); ++j) {
      const StencilTable s = BuildButterflyStencils(hierarchy, j);
      const size_t coarse = values.size();
      values.resize(coarse + s.size());
      for (size_t k = 0; k < s.size(); ++k) {
        double sum = 0.0;
        for (uint32_t e = s.offsets[k]; e < s.offsets[k + 1]; ++e) sum += s.weights[e] * values[s.indices[e]];
        values[coarse + k] = sum;
      }
    }
    double energy = 0.0;
    for (double v : values) energy += v * v;
    weights[i] = energy;
  }
  return weights;
}

void ExpectSameAsDense(const SemiRegularHierarchy& hierarchy) {
  const std::vector<double> sparse = BaseInfluenceWeights(hierarchy);
  const std::vector<double> dense = DenseInfluenceWeights(hierarchy);
  ASSERT_EQ(sparse.size(), dense.size());
  for (size_t i = 0; i < dense.size(); ++i) {
    EXPECT_EQ(sparse[i], dense[i]) << "base vertex " << i;
    // Interpolating subdivision keeps the impulse's 1 at its own vertex.
    EXPECT_GE(sparse[i], 1.0) << "base vertex " << i;
  }
}

TEST(BaseInfluence, ClosedMeshMatchesDenseRefinementBitForBit) {
  ExpectSameAsDense(MakeBumpySphere(3).hierarchy);
}

TEST(BaseInfluence, BoundaryMatchesDenseRefinementBitForBit) {
  const Mesh disc = MakeDisc(3);
  auto hierarchy = SemiRegularHierarchy::Build(static_cast<uint32_t>(disc.positions.size()), disc.faces, 3);
  ASSERT_TRUE(hierarchy.ok()) << hierarchy.status().ToString();
  ExpectSameAsDense(*hierarchy);
}

TEST(BaseInfluence, NoLevelsIsTheImpulseAlone) {
  const SemiRegularMesh sphere = MakeBumpySphere(0);
  const std::vector<double> w = BaseInfluenceWeights(sphere.hierarchy);
  ASSERT_EQ(w.size(), sphere.hierarchy.NumVertices(0));
  for (double x : w) EXPECT_EQ(x, 1.0);
}

}  // namespace
}  // namespace eqmesh::testing

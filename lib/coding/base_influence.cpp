#include "coding/base_influence.h"

#include "wavelet/butterfly.h"

namespace eqmesh {
namespace {

// Scalar version of ApplyStencils: the impulse is one number per vertex.
void RefineScalar(const StencilTable& s, std::vector<double>* values) {
  const size_t coarse = values->size();
  values->resize(coarse + s.size());
  for (size_t k = 0; k < s.size(); ++k) {
    double sum = 0.0;
    for (uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) sum += s.weights[i] * (*values)[s.indices[i]];
    (*values)[coarse + k] = sum;
  }
}

}  // namespace

std::vector<double> BaseInfluenceWeights(const SemiRegularHierarchy& hierarchy) {
  const uint32_t base = hierarchy.NumVertices(0);
  std::vector<StencilTable> stencils;
  for (int j = 0; j < hierarchy.levels(); ++j) stencils.push_back(BuildButterflyStencils(hierarchy, j));
  std::vector<double> weights(base, 1.0);
  std::vector<double> values;
  for (uint32_t i = 0; i < base; ++i) {
    values.assign(base, 0.0);
    values[i] = 1.0;
    for (const StencilTable& s : stencils) RefineScalar(s, &values);
    double energy = 0.0;
    for (const double v : values) energy += v * v;
    weights[i] = energy;
  }
  return weights;
}

}  // namespace eqmesh

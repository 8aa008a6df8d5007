#include "coding/level_decoder.h"

#include <array>
#include <cmath>
#include <string>

#include "coding/entropy/range_coder.h"
#include "coding/eq/eq_decoder.h"
#include "coding/eq/eq_layout.h"
#include "coding/uniform_model.h"

namespace eqmesh {
namespace {

using uniform_coder::kMaxEscapePrefix;
using uniform_coder::ComponentModel;
using uniform_coder::kUnaryLimit;

int64_t DecodeSymbol(RangeDecoder* rc, ComponentModel* m) {
  if (rc->DecodeBit(&m->zero) == 0) return 0;
  const bool negative = rc->DecodeBits(1) != 0;
  int64_t magnitude = 1;
  int i = 0;
  while (i < kUnaryLimit && rc->DecodeBit(&m->unary[i]) == 1) {
    ++magnitude;
    ++i;
  }
  if (i == kUnaryLimit) magnitude += rc->DecodeExpGolomb(0, kMaxEscapePrefix);
  return negative ? -magnitude : magnitude;
}

StatusOr<std::vector<Vec3>> DecodeUniform(const LevelCodingParams& params, uint32_t count,
                                          const uint8_t* data, size_t size, int j) {
  // Each coefficient costs at least three adaptive zero flags, and an AdaptiveBit
  // never gives a symbol more than 4065/4096 (at most ~0.99268 of the range after
  // rounding): >= 0.0318 bits a coefficient, so `size` bytes hold fewer than
  // 252 * size. More is a corrupt chunk, refused before allocating for it.
  if (count > uint64_t{256} * size) {
    return CorruptStream("level chunk " + std::to_string(j) + ": " + std::to_string(size) +
                         " bytes cannot hold " + std::to_string(count) + " uniform-coded coefficients");
  }
  RangeDecoder rc(data, size);
  std::array<ComponentModel, 3> models;
  const double steps[3] = {UniformStep(params, false), UniformStep(params, true),
                           UniformStep(params, true)};
  std::vector<Vec3> out(count);
  for (uint32_t k = 0; k < count; ++k) {
    for (int c = 0; c < 3; ++c) {
      out[k][c] = static_cast<double>(DecodeSymbol(&rc, &models[c])) * steps[c];
    }
    // A hostile chunk runs past its end quickly; stop at the first sign of it.
    if (!rc.ok()) break;
  }
  if (!rc.ok()) {
    return CorruptStream("level chunk " + std::to_string(j) + ": uniform coder data corrupt or truncated");
  }
  EQMESH_RETURN_IF_ERROR(rc.CheckConsumedAll("level chunk " + std::to_string(j)));
  return out;
}

StatusOr<std::vector<Vec3>> DecodeEqCoefficients(const LevelCodingParams& params,
                                                 const SemiRegularHierarchy& hierarchy, int j,
                                                 const uint8_t* data, size_t size) {
  // The chunk must declare this level's coefficient count before the layout (the
  // level's largest allocation) is built for it.
  const int64_t declared = PeekEqLevelCount(data, size);
  if (declared != hierarchy.NumOddVertices(j)) {
    return CorruptStream("eqm level chunk " + std::to_string(j) + ": " +
                         (declared < 0 ? std::string("too short for its side information")
                                       : "declares " + std::to_string(declared) + " coefficients, the level has " +
                                             std::to_string(hierarchy.NumOddVertices(j))));
  }
  const uint32_t count = hierarchy.NumOddVertices(j);
  auto empty = EqLevelCodesNothing(data, size, count, params.tangential_context, j);
  if (!empty.ok()) return empty.status().WithContext("eqm level chunk " + std::to_string(j));
  if (*empty) return std::vector<Vec3>();
  EQMESH_ASSIGN_OR_RETURN(EqLevelLayout layout, BuildEqLevelLayout(hierarchy, j));
  auto local = DecodeEqLevel(layout, data, size, params.quantum, params.tangential_context);
  if (!local.ok()) return local.status().WithContext("eqm level chunk " + std::to_string(j));
  return local;
}

}  // namespace

double UniformStep(const LevelCodingParams& params, bool tangential) {
  const double lambda = tangential ? params.lambda / params.tangential_factor : params.lambda;
  return params.quantum * std::sqrt(6.0 / (lambda * std::log(2.0)));
}

StatusOr<std::vector<Vec3>> DecodeLevelCoefficients(const LevelCodingParams& params,
                                                    const SemiRegularHierarchy& hierarchy, int j,
                                                    const uint8_t* data, size_t size) {
  const uint32_t count = hierarchy.NumOddVertices(j);
  switch (params.coder) {
    case bitstream::CoderId::kUniform:
      return DecodeUniform(params, count, data, size, j);
    case bitstream::CoderId::kEq:
      return DecodeEqCoefficients(params, hierarchy, j, data, size);
    case bitstream::CoderId::kZerotree:
      break;
  }
  return UnsupportedFeature("level coder " + std::to_string(static_cast<int>(params.coder)) +
                            " is not in this build");
}

}  // namespace eqmesh

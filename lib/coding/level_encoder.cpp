#include "coding/level_encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "coding/entropy/range_coder.h"
#include "coding/eq/eq_encoder.h"
#include "coding/uniform_model.h"

namespace eqmesh {
namespace {

using uniform_coder::kMaxEscapePrefix;
using uniform_coder::ComponentModel;
using uniform_coder::kUnaryLimit;

// Largest magnitude the decoder accepts (Exp-Golomb escape with kMaxEscapePrefix).
constexpr int64_t kMaxMagnitude = kUnaryLimit + (int64_t{1} << kMaxEscapePrefix);

// Chunk lambda code added per level below the finest (1/16 octave units).
constexpr int32_t kLevelLambdaCodePerLevel = 16;

void EncodeSymbol(RangeEncoder* rc, ComponentModel* m, int64_t q) {
  rc->EncodeBit(&m->zero, q != 0);
  if (q == 0) return;
  rc->EncodeBits(q < 0 ? 1u : 0u, 1);
  const int64_t extra = std::llabs(q) - 1;
  for (int i = 0; i < kUnaryLimit; ++i) {
    const int bit = extra > i ? 1 : 0;
    rc->EncodeBit(&m->unary[i], bit);
    if (!bit) return;
  }
  rc->EncodeExpGolomb(static_cast<uint32_t>(extra - kUnaryLimit), 0);
}

std::vector<uint8_t> EncodeUniform(const LevelCodingParams& params, const std::vector<Vec3>& local,
                                   std::vector<Vec3>* reconstructed) {
  RangeEncoder rc;
  std::array<ComponentModel, 3> models;
  const double steps[3] = {UniformStep(params, false), UniformStep(params, true),
                           UniformStep(params, true)};
  reconstructed->resize(local.size());
  for (size_t k = 0; k < local.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const double scaled = std::clamp(local[k][c] / steps[c], -double(kMaxMagnitude),
                                       double(kMaxMagnitude));
      const int64_t q = std::llround(scaled);
      EncodeSymbol(&rc, &models[c], q);
      (*reconstructed)[k][c] = static_cast<double>(q) * steps[c];
    }
  }
  return rc.Finish();
}

// A coefficient's error at refinement j is never revisited at its own vertex and
// reaches, through every finer prediction that is not corrected, an area ~4x
// larger per level coarser; closed-loop coding corrects part of it. So the chunk's
// lambda doubles per level from the finest towards the base (one octave, code 16
// per level; the EQ side information carries each chunk's code, the decoder needs
// nothing else). One octave gains 0.6-2.7 dB over a single lambda at 1 and 4 bpv and
// stays within 0.45 dB of the best of 0-1.5 octaves there (measured:
// bench/log/2026-12-05-codec-notebook.md).
int32_t LevelLambdaOffset(int levels, int j) {
  return kLevelLambdaCodePerLevel * (levels - 1 - j);
}

StatusOr<std::vector<uint8_t>> EncodeEq(const LevelCodingParams& params, const SemiRegularHierarchy& hierarchy,
                                        int j, const EqLevelLayout& layout, const std::vector<Vec3>& local,
                                        std::vector<Vec3>* reconstructed) {
  EqEncodeOptions options;
  // Both codes are 16 log2(lambda q0^2): the header's code is the EQ code.
  options.lambda_code = static_cast<int32_t>(params.lambda_code) + LevelLambdaOffset(hierarchy.levels(), j);
  // The header's factor divides lambda for the tangential parts; the EQ coder's
  // scale multiplies it.
  options.tangential_lambda_scale = 1.0 / params.tangential_factor;
  options.tangential_context = params.tangential_context;
  return EncodeEqLevel(layout, local, params.quantum, options, reconstructed);
}

}  // namespace

StatusOr<std::vector<uint8_t>> EncodeLevelCoefficients(const LevelCodingParams& params,
                                                       const SemiRegularHierarchy& hierarchy,
                                                       int j, const std::vector<Vec3>& local,
                                                       std::vector<Vec3>* reconstructed,
                                                       const EqLevelLayout* eq_layout) {
  if (local.size() != hierarchy.NumOddVertices(j)) {
    return InternalError("level " + std::to_string(j) + " coefficient count mismatch");
  }
  switch (params.coder) {
    case bitstream::CoderId::kUniform:
      return EncodeUniform(params, local, reconstructed);
    case bitstream::CoderId::kEq:
      if (eq_layout == nullptr || eq_layout->level != j || eq_layout->size() != local.size()) {
        return InternalError("level " + std::to_string(j) + " coded without its EQ layout");
      }
      return EncodeEq(params, hierarchy, j, *eq_layout, local, reconstructed);
    case bitstream::CoderId::kZerotree:
      break;
  }
  return UnsupportedFeature("level coder not in this build");
}

}  // namespace eqmesh

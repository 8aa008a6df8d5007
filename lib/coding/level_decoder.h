// Decoder half of the per-level coefficient coders: one level chunk -> the local
// wavelet coefficients (normal, tangent, bitangent components) of the odd vertices
// of one refinement. The coder is selected by the header's CoderId.
//
// kUniform (a baseline of ours, not from the papers): every component is quantized
// with a uniform mid-tread quantizer whose step follows from lambda by the
// high-rate entropy-coded rule D = step^2/12, R = h - log2(step), hence
// lambda = -dR/dD = 6 / (step^2 ln 2) per squared world unit; tangential components
// use lambda / tangential_factor (Lavu et al. 2003 sec. 3.3: tangential errors
// matter less). Symbols: adaptive zero flag, bypass sign, adaptive unary magnitude
// up to kUnaryLimit then order-0 Exp-Golomb, contexts per component.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/bitstream_shared.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// What every level coder receives; the decoder rebuilds it from the header.
struct LevelCodingParams {
  bitstream::CoderId coder = bitstream::CoderId::kEq;
  int64_t lambda_code = 0;          // header code: lambda = 2^(code / kLogCodeScale)
  double lambda = 1.0;              // per squared quantum (bitstream_shared.h)
  double tangential_factor = 1.0;  // EncodeOptions::tangential_factor
  double quantum = 1.0;             // q0, world units
  bool tangential_context = false;  // EQ: header flag kTangentialContext (1.3)
};

// Uniform coder step for the normal (tangential = false) or tangential components.
double UniformStep(const LevelCodingParams& params, bool tangential);

// Decodes the coefficients of refinement j -> j+1 (NumOddVertices(j) entries, each
// (normal, tangent, bitangent) in world units along the local frame), or an empty
// vector when the chunk makes every coefficient zero (a fine level at a low rate:
// no layout is built and nothing is allocated for it).
StatusOr<std::vector<Vec3>> DecodeLevelCoefficients(const LevelCodingParams& params,
                                                    const SemiRegularHierarchy& hierarchy, int j,
                                                    const uint8_t* data, size_t size);

namespace uniform_coder {
constexpr int kUnaryLimit = 14;
constexpr int kMaxEscapePrefix = 24;  // magnitudes stay below 2^25
}  // namespace uniform_coder

}  // namespace eqmesh

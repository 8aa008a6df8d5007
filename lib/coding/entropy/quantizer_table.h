// Runtime access to the normative quantizer tables (quantizer_tables.inc, generated
// offline by generate_quantizer_tables.cpp from the model in dead_zone_quantizer.h).
// Encoder and decoder select entries with integers only, so both pick the same
// quantizer on any compiler (Lavu, Choi, Baraniuk 2003: "the bin probabilities for
// each quantizer from the R-D table are computed off-line").
//
// Entry semantics, in units of the coefficient's sigma (Q16 fixed point):
//   index 0:           |x| <= dead_zone
//   index k >= 1:      dead_zone + (k-1) step < |x| <= dead_zone + k step,
//                      reconstructed at dead_zone + (k-1) step + recon_offset[min(k, M) - 1]
//   magnitudes >= M share the open symbol M; the excess |q| - M follows as an escape.
// step == 0 means "code nothing": every coefficient is zero and no symbol is coded.
#pragma once

#include <cstdint>

#include "coding/entropy/dead_zone_quantizer.h"

namespace eqmesh {

struct QuantizerEntry {
  int32_t step_q16 = 0;
  int32_t dead_zone_q16 = 0;
  int32_t max_index = 0;             // M
  const uint16_t* freq = nullptr;    // M + 1 magnitude frequencies, sum 2^kFreqBits
  const int32_t* recon_offset = nullptr;  // M offsets, Q16 of sigma

  bool codes_nothing() const { return step_q16 == 0; }
  // Reconstruction magnitude of index k >= 1, Q16 of sigma (exact integer rule).
  int64_t ReconstructionQ16(int64_t k) const;
};

// Number of shapes / buckets and the bucket grid, as in QuantizerTableLayout.
inline constexpr int kQuantizerShapeCount = QuantizerTableLayout::kShapeCount;
inline constexpr int kQuantizerBucketCount = QuantizerTableLayout::kBucketCount;
inline constexpr int kQuantizerFreqBits = QuantizerTableLayout::kFreqBits;

// Bucket of log2(lambda sigma^2) given in 1/16 octaves: -1 below the table ("code
// nothing"), clamped to the last bucket above it.
int QuantizerBucket(int64_t log2_lambda_sigma2_sixteenths);

// The entry for a shape index in [0, kQuantizerShapeCount) and a bucket from
// QuantizerBucket; bucket -1 gives the shared code-nothing entry. Out-of-range
// arguments are clamped (callers validate stream values before getting here).
const QuantizerEntry& GetQuantizer(int shape_index, int bucket);

}  // namespace eqmesh

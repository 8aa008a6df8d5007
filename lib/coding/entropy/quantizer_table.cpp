// Quantizer table access: see quantizer_table.h.
#include "coding/entropy/quantizer_table.h"

#include <array>

namespace eqmesh {
namespace {

#include "coding/entropy/quantizer_tables.inc"

using Layout = QuantizerTableLayout;
constexpr int kEntryCount = Layout::kShapeCount * Layout::kBucketCount;
static_assert(sizeof(kEntries) / sizeof(kEntries[0]) == 5 * kEntryCount,
              "quantizer_tables.inc does not match QuantizerTableLayout");

std::array<QuantizerEntry, kEntryCount> BuildEntries() {
  std::array<QuantizerEntry, kEntryCount> out{};
  for (int i = 0; i < kEntryCount; ++i) {
    const int32_t* e = &kEntries[5 * i];
    out[i].step_q16 = e[0];
    out[i].dead_zone_q16 = e[1];
    out[i].max_index = e[2];
    out[i].freq = &kFreq[e[3]];
    out[i].recon_offset = &kRecon[e[4]];
  }
  return out;
}

int FloorDiv(int64_t a, int64_t b) {
  int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return static_cast<int>(q);
}

}  // namespace

int64_t QuantizerEntry::ReconstructionQ16(int64_t k) const {
  if (k <= 0 || max_index <= 0) return 0;
  const int64_t slot = k < max_index ? k : max_index;
  return dead_zone_q16 + (k - 1) * static_cast<int64_t>(step_q16) + recon_offset[slot - 1];
}

int QuantizerBucket(int64_t t) {
  // Clamp first so the division below never sees extreme values.
  if (t < -(int64_t{1} << 40)) return -1;
  if (t > (int64_t{1} << 40)) return Layout::kBucketCount - 1;
  const int quarter = FloorDiv(t, 4);
  const int bucket = quarter - Layout::kBucketMinQuarter;
  if (bucket < 0) return -1;
  return bucket < Layout::kBucketCount ? bucket : Layout::kBucketCount - 1;
}

const QuantizerEntry& GetQuantizer(int shape_index, int bucket) {
  static const std::array<QuantizerEntry, kEntryCount> entries = BuildEntries();
  static const QuantizerEntry nothing{};
  if (bucket < 0) return nothing;
  if (shape_index < 0) shape_index = 0;
  if (shape_index >= Layout::kShapeCount) shape_index = Layout::kShapeCount - 1;
  if (bucket >= Layout::kBucketCount) bucket = Layout::kBucketCount - 1;
  const QuantizerEntry& e = entries[shape_index * Layout::kBucketCount + bucket];
  return e.codes_nothing() ? nothing : e;
}

}  // namespace eqmesh

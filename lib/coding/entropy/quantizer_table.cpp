// Quantizer table access: see quantizer_table.h.
//
// quantizer_tables.inc holds the tables packed: as plain arrays they were 490 KB (118 KB
// gzipped) of the 646 KB WebAssembly decoder, packed 84 KB (38 KB). They are unpacked once,
// on first use, with integers only (0.6 ms native, 0.8 ms as wasm).
// Format (generate_quantizer_tables.cpp): three streams of residuals, entries shape-major;
// 1: step, dead zone, M minus the previous bucket's; 2, 3: per coded entry freq[0..M-1]
// (freq[M] = 2^15 - their sum), recon[0..M-1], each term minus PredictTerm and, for the first
// kCrossBucketTerms, minus that term's residual in the shape's previous coded entry.
#include "coding/entropy/quantizer_table.h"

#include <array>
#include <cassert>
#include <cstddef>
#include <vector>

namespace eqmesh {
namespace {

#include "coding/entropy/quantizer_tables.inc"

using Layout = QuantizerTableLayout;
constexpr int kEntryCount = Layout::kShapeCount * Layout::kBucketCount;
static_assert(sizeof(kPackedQuantizerTables) ==
                  static_cast<size_t>(kPackedHeaderBytes + kPackedFreqBytes + kPackedReconBytes),
              "quantizer_tables.inc: stream sizes do not add up");

// The packing rules of generate_quantizer_tables.cpp.
constexpr int kCrossBucketTerms = 8;
constexpr int kFreqHeldTerms = 3;   // freq[1], freq[2] predicted by the term before
constexpr int kReconHeldTerms = 2;  // recon[1] predicted by recon[0]

// One stream of residuals (ResidualWriter in generate_quantizer_tables.cpp), LEB128 tokens:
// odd 2u - 1, one nonzero residual of zig-zag code u; even 2(n - 1), a run of n zeros.
class ResidualReader {
 public:
  explicit ResidualReader(const uint8_t* at) : at_(at) {}
  bool EndsAt(const uint8_t* end) const { return at_ == end && zeros_ == 0; }
  int64_t Next() {
    if (zeros_ > 0) {
      --zeros_;
      return 0;
    }
    const uint64_t token = NextToken();
    if (token % 2 == 0) {
      zeros_ = token / 2;
      return 0;
    }
    const uint64_t u = (token + 1) / 2;
    return static_cast<int64_t>(u >> 1) ^ -static_cast<int64_t>(u & 1);
  }

 private:
  uint64_t NextToken() {
    uint64_t t = 0;
    for (int shift = 0;; shift += 7) {
      const uint8_t byte = *at_++;
      t |= static_cast<uint64_t>(byte & 0x7f) << shift;
      if (byte < 0x80) return t;
    }
  }

  const uint8_t* at_;
  uint64_t zeros_ = 0;
};

// Bins of a GGD tail shrink roughly geometrically: a^2 / b continues the ratio of b, a.
// Flat runs (a == b) give a without a division: the same value, unpacking 25 % faster.
int64_t Geometric(int64_t a, int64_t b) { return b > 0 && a != b ? (a * a + b / 2) / b : a; }

int64_t PredictTerm(const int64_t* x, int k, int64_t first, int held_terms) {
  if (k == 0) return first;
  if (k < held_terms) return x[k - 1];
  return Geometric(x[k - 1], x[k - 2]);
}

// First residuals of the shape's previous coded entry, for one kind of sequence.
struct PreviousResiduals {
  std::array<int64_t, kCrossBucketTerms> r{};
  int count = 0;
};

void UnpackSequence(ResidualReader& in, int count, int64_t first, int held_terms,
                    PreviousResiduals& previous, int64_t* x) {
  PreviousResiduals current;
  for (int k = 0; k < count; ++k) {
    int64_t r = in.Next();
    if (k < kCrossBucketTerms) {
      if (k < previous.count) r += previous.r[k];
      current.r[k] = r;
      current.count = k + 1;
    }
    x[k] = PredictTerm(x, k, first, held_terms) + r;
  }
  previous = current;
}

struct Tables {
  std::vector<uint16_t> freq;
  std::vector<int32_t> recon;
  std::array<QuantizerEntry, kEntryCount> entries{};
};

Tables UnpackTables() {
  Tables t;
  t.freq.reserve(kUnpackedFreqCount);
  t.recon.reserve(kUnpackedReconCount);
  std::array<size_t, kEntryCount> freq_at{}, recon_at{};
  const uint8_t* const freq_start = kPackedQuantizerTables + kPackedHeaderBytes;
  const uint8_t* const recon_start = freq_start + kPackedFreqBytes;
  ResidualReader headers(kPackedQuantizerTables), freq_in(freq_start), recon_in(recon_start);
  std::array<int64_t, Layout::kMaxIndexCap> x{};
  for (int s = 0; s < Layout::kShapeCount; ++s) {
    int64_t step = 0, dead_zone = 0, m = 0;
    PreviousResiduals previous_freq, previous_recon;
    for (int b = 0; b < Layout::kBucketCount; ++b) {
      step += headers.Next();
      dead_zone += headers.Next();
      m += headers.Next();
      const int i = s * Layout::kBucketCount + b;
      QuantizerEntry& e = t.entries[i];
      e.step_q16 = static_cast<int32_t>(step);
      e.dead_zone_q16 = static_cast<int32_t>(dead_zone);
      e.max_index = static_cast<int32_t>(m);
      if (step == 0) continue;
      assert(m >= 1 && m <= Layout::kMaxIndexCap);
      freq_at[i] = t.freq.size();
      UnpackSequence(freq_in, e.max_index, 0, kFreqHeldTerms, previous_freq, x.data());
      int64_t sum = 0;
      for (int k = 0; k < e.max_index; ++k) {
        t.freq.push_back(static_cast<uint16_t>(x[k]));
        sum += x[k];
      }
      t.freq.push_back(static_cast<uint16_t>((int64_t{1} << Layout::kFreqBits) - sum));
      recon_at[i] = t.recon.size();
      UnpackSequence(recon_in, e.max_index, step / 2, kReconHeldTerms, previous_recon, x.data());
      for (int k = 0; k < e.max_index; ++k) t.recon.push_back(static_cast<int32_t>(x[k]));
    }
  }
  assert(headers.EndsAt(freq_start) && freq_in.EndsAt(recon_start) &&
         recon_in.EndsAt(kPackedQuantizerTables + sizeof(kPackedQuantizerTables)));
  assert(t.freq.size() == static_cast<size_t>(kUnpackedFreqCount) &&
         t.recon.size() == static_cast<size_t>(kUnpackedReconCount));
  // Pointers last: the vectors no longer grow.
  for (int i = 0; i < kEntryCount; ++i) {
    if (t.entries[i].codes_nothing()) continue;
    t.entries[i].freq = t.freq.data() + freq_at[i];
    t.entries[i].recon_offset = t.recon.data() + recon_at[i];
  }
  return t;
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
  // Unpacked on first use; a function-local static is initialised once, thread-safely.
  static const Tables tables = UnpackTables();
  static const QuantizerEntry nothing{};
  if (bucket < 0) return nothing;
  if (shape_index < 0) shape_index = 0;
  if (shape_index >= Layout::kShapeCount) shape_index = Layout::kShapeCount - 1;
  if (bucket >= Layout::kBucketCount) bucket = Layout::kBucketCount - 1;
  const QuantizerEntry& e = tables.entries[shape_index * Layout::kBucketCount + bucket];
  return e.codes_nothing() ? nothing : e;
}

}  // namespace eqmesh

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "coding/entropy/range_coder.h"

namespace eqmesh {
namespace {

struct Alphabet {
  int total_bits;
  std::vector<uint32_t> freq;
  std::vector<uint32_t> cum;
};

// Random distribution over n symbols summing to 2^total_bits, every freq >= 1.
Alphabet RandomAlphabet(std::mt19937* rng, int n, int total_bits) {
  Alphabet a{total_bits, std::vector<uint32_t>(n, 1), {}};
  const uint32_t total = 1u << total_bits;
  std::uniform_int_distribution<int> pick(0, n - 1);
  // Skewed: some symbols get much more mass than others.
  for (uint32_t left = total - static_cast<uint32_t>(n); left > 0;) {
    const uint32_t chunk = std::min<uint32_t>(left, 1 + static_cast<uint32_t>((*rng)() % (total / 8 + 1)));
    a.freq[pick(*rng)] += chunk;
    left -= chunk;
  }
  uint32_t c = 0;
  for (uint32_t f : a.freq) {
    a.cum.push_back(c);
    c += f;
  }
  return a;
}

int SampleSymbol(std::mt19937* rng, const Alphabet& a) {
  const uint32_t v = static_cast<uint32_t>((*rng)()) & ((1u << a.total_bits) - 1);
  int s = 0;
  while (s + 1 < static_cast<int>(a.cum.size()) && a.cum[s + 1] <= v) ++s;
  return s;
}

int FindSymbol(const Alphabet& a, uint32_t v) {
  int s = 0;
  while (s + 1 < static_cast<int>(a.cum.size()) && a.cum[s + 1] <= v) ++s;
  return s;
}

TEST(RangeCoder, RoundTripsMixedSymbolsBitsAndGolomb) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Alphabet> alphabets;
    for (int i = 0; i < 4; ++i) {
      const int bits = 1 + static_cast<int>(rng() % 16);
      const int n = 1 + static_cast<int>(rng() % std::min<uint32_t>(300, 1u << bits));
      alphabets.push_back(RandomAlphabet(&rng, n, bits));
    }
    struct Op { int kind; int which; uint32_t value; int n; };
    std::vector<Op> ops;
    const int count = 1 + static_cast<int>(rng() % 3000);
    for (int i = 0; i < count; ++i) {
      const int kind = static_cast<int>(rng() % 4);
      if (kind == 0) {
        const int w = static_cast<int>(rng() % 4);
        ops.push_back({0, w, static_cast<uint32_t>(SampleSymbol(&rng, alphabets[w])), 0});
      } else if (kind == 1) {
        ops.push_back({1, static_cast<int>(rng() % 3), (rng() % 10) < 8 ? 0u : 1u, 0});
      } else if (kind == 2) {
        const int n = static_cast<int>(rng() % 33);
        const uint32_t r = static_cast<uint32_t>(rng());
        ops.push_back({2, 0, n == 32 ? r : (r & ((1u << n) - 1)), n});
      } else {
        const int k = static_cast<int>(rng() % 4);
        const uint32_t r = static_cast<uint32_t>(rng());
        ops.push_back({3, 0, r >> (rng() % 32), k});
      }
    }
    RangeEncoder enc;
    AdaptiveBit enc_models[3];
    for (const Op& op : ops) {
      if (op.kind == 0) {
        const Alphabet& a = alphabets[op.which];
        enc.EncodeSymbol(a.cum[op.value], a.freq[op.value], a.total_bits);
      } else if (op.kind == 1) {
        enc.EncodeBit(&enc_models[op.which], static_cast<int>(op.value));
      } else if (op.kind == 2) {
        enc.EncodeBits(op.value, op.n);
      } else {
        enc.EncodeExpGolomb(op.value, op.n);
      }
    }
    const std::vector<uint8_t> bytes = enc.Finish();
    RangeDecoder dec(bytes.data(), bytes.size());
    AdaptiveBit dec_models[3];
    for (size_t i = 0; i < ops.size(); ++i) {
      const Op& op = ops[i];
      uint32_t got;
      if (op.kind == 0) {
        const Alphabet& a = alphabets[op.which];
        const int s = FindSymbol(a, dec.DecodeFreq(a.total_bits));
        dec.Consume(a.cum[s], a.freq[s]);
        got = static_cast<uint32_t>(s);
      } else if (op.kind == 1) {
        got = static_cast<uint32_t>(dec.DecodeBit(&dec_models[op.which]));
      } else if (op.kind == 2) {
        got = dec.DecodeBits(op.n);
      } else {
        got = dec.DecodeExpGolomb(op.n, 32);
      }
      ASSERT_EQ(got, op.value) << "trial " << trial << " op " << i << " kind " << op.kind;
    }
    EXPECT_TRUE(dec.ok());
    EXPECT_EQ(dec.position(), bytes.size());
  }
}

TEST(RangeCoder, CompressesNearEntropy) {
  std::mt19937 rng(7);
  const Alphabet a = RandomAlphabet(&rng, 20, 15);
  double entropy_bits = 0;
  RangeEncoder enc;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const int s = SampleSymbol(&rng, a);
    entropy_bits -= std::log2(a.freq[s] / 32768.0);
    enc.EncodeSymbol(a.cum[s], a.freq[s], 15);
  }
  const double bits = 8.0 * static_cast<double>(enc.Finish().size());
  EXPECT_LT(bits, entropy_bits * 1.001 + 64);
}

TEST(RangeCoder, AdaptiveBitLearnsSkew) {
  std::mt19937 rng(3);
  RangeEncoder enc;
  AdaptiveBit m;
  const int n = 100000;
  for (int i = 0; i < n; ++i) enc.EncodeBit(&m, rng() % 100 < 3 ? 1 : 0);
  // h(0.03) = 0.194 bits; adaptation costs a little.
  EXPECT_LT(static_cast<double>(enc.Finish().size()) * 8.0, n * 0.215);
}

TEST(RangeCoder, CarryChainsSurvive) {
  // Symbols at the very top of the interval force long runs of 0xFF and carries.
  RangeEncoder enc;
  const int n = 5000;
  for (int i = 0; i < n; ++i) enc.EncodeSymbol(65535, 1, 16);
  for (int i = 0; i < n; ++i) enc.EncodeSymbol(0, 1, 16);
  for (int i = 0; i < n; ++i) enc.EncodeSymbol(i % 2 ? 65535u : 1u, 1, 16);
  const std::vector<uint8_t> bytes = enc.Finish();
  RangeDecoder dec(bytes.data(), bytes.size());
  for (int i = 0; i < 3 * n; ++i) {
    const uint32_t want = i < n ? 65535u : i < 2 * n ? 0u : ((i - 2 * n) % 2 ? 65535u : 1u);
    const uint32_t v = dec.DecodeFreq(16);
    ASSERT_EQ(v, want) << i;
    dec.Consume(v, 1);
  }
  EXPECT_TRUE(dec.ok());
}

TEST(RangeCoder, TruncatedOrEmptyInputSetsStickyError) {
  RangeEncoder enc;
  for (int i = 0; i < 1000; ++i) enc.EncodeBits(static_cast<uint32_t>(i) & 0xFF, 8);
  const std::vector<uint8_t> bytes = enc.Finish();
  for (size_t len : {size_t{0}, size_t{1}, size_t{3}, bytes.size() / 2, bytes.size() - 1}) {
    RangeDecoder dec(bytes.data(), len);
    for (int i = 0; i < 1000; ++i) (void)dec.DecodeBits(8);
    EXPECT_FALSE(dec.ok()) << len;
  }
  RangeDecoder null_dec(nullptr, 0);
  (void)null_dec.DecodeBits(8);
  EXPECT_FALSE(null_dec.ok());
}

TEST(RangeCoder, GarbageNeverHangsInExpGolomb) {
  std::vector<uint8_t> zeros(64, 0);
  RangeDecoder dec(zeros.data(), zeros.size());
  (void)dec.DecodeExpGolomb(0, 24);
  EXPECT_FALSE(dec.ok());
}

}  // namespace
}  // namespace eqmesh

// Shared EQ model: see eq_model.h for the papers followed and the departures.
#include "coding/eq/eq_model.h"

#include <algorithm>

namespace eqmesh {
namespace {

// ceil(2^31 * 2^(i/16)): m >= kLogThreshold[i] exactly when log2(m) >= 31 + i/16.
constexpr uint32_t kLogThreshold[16] = {
    2147483648u, 2242560872u, 2341847524u, 2445529972u, 2553802834u, 2666869345u,
    2784941738u, 2908241643u, 3037000500u, 3171460000u, 3311872530u, 3458501654u,
    3611622603u, 3771522797u, 3938502376u, 4112874774u};

// round(2^30 * 2^(f/32)).
constexpr int64_t kPow2Frac32[32] = {
    1073741824, 1097253708, 1121280436, 1145833280, 1170923762, 1196563654, 1222764986,
    1249540052, 1276901417, 1304861917, 1333434672, 1362633090, 1392470869, 1422962010,
    1454120821, 1485961921, 1518500250, 1551751076, 1585730000, 1620452965, 1655936265,
    1692196547, 1729250827, 1767116489, 1805811301, 1845353420, 1885761398, 1927054196,
    1969251188, 2012372174, 2056437387, 2101467502};

int32_t FloorDiv32(int32_t a, int32_t b) {
  int32_t q = a / b;
  if (a % b != 0 && a < 0) --q;
  return q;
}

// sigma = 2^(log_sigma2 / 32) q0, as Q16.
int64_t SigmaQ16(int32_t log_sigma2) {
  const int32_t e = FloorDiv32(log_sigma2, 32);
  const int64_t mantissa = kPow2Frac32[log_sigma2 - 32 * e];  // Q30
  const int shift = e - 14;
  return shift >= 0 ? mantissa << shift : mantissa >> (-shift);
}

uint32_t ReadSigned(RangeDecoder* dec, int bits, int32_t* value) {
  const uint32_t raw = dec->DecodeBits(bits);
  *value = static_cast<int32_t>(raw) - (1 << (bits - 1));
  return raw;
}

bool DecodeClass(RangeDecoder* dec, int32_t lo, int32_t hi, EqGgdClass* c) {
  c->present = dec->DecodeBits(1) != 0;
  if (!c->present) return true;
  c->shape = static_cast<uint8_t>(dec->DecodeBits(kEqShapeBits));
  ReadSigned(dec, kEqLogBits, &c->log_sigma2);
  return c->shape < kQuantizerShapeCount && c->log_sigma2 >= lo && c->log_sigma2 <= hi;
}

// Index of the highest set bit of x > 0.
int HighestBit(uint64_t x) {
#if defined(__GNUC__)
  return 63 - __builtin_clzll(x);
#else
  int e = 0;
  while ((x >> e) > 1) ++e;
  return e;
#endif
}

// Log2Sixteenths of a value below 2^64: the same rule, without 128-bit shifts.
int32_t Log2Sixteenths64(uint64_t x) {
  const int e = HighestBit(x);
  const uint32_t m = static_cast<uint32_t>(e >= 31 ? (x >> (e - 31)) : (x << (31 - e)));
  int f = 15;
  while (f > 0 && m < kLogThreshold[f]) --f;
  return 16 * e + f;
}

}  // namespace

int32_t Log2Sixteenths(EqUint128 x) {
  if ((x >> 64) == 0) return Log2Sixteenths64(static_cast<uint64_t>(x));
  int e = 64 + HighestBit(static_cast<uint64_t>(x >> 64));
  const uint32_t m = static_cast<uint32_t>(x >> (e - 31));
  int f = 15;
  while (f > 0 && m < kLogThreshold[f]) --f;
  return 16 * e + f;
}

bool EstimateLogSigma2(const int64_t* recon, const EqContextTerms& terms, size_t p,
                       int32_t* log_sigma2) {
  EqUint128 sum = 0;
  uint64_t weight = 0;
  terms.ForEach(p, [&](size_t n, uint32_t w) {
    const int64_t r = recon[n];
    sum += static_cast<EqUint128>(static_cast<uint64_t>(r * r)) * w;
    weight += w;
  });
  if (sum == 0) return false;
  // 2^16 headroom keeps 1/16-octave resolution for small sums. Sums below 2^47
  // (all but absurd coefficients) take the same quotient in 64 bits.
  int32_t log_mean = 0;
  if (sum < (static_cast<EqUint128>(1) << 47)) {
    const uint64_t mean = (static_cast<uint64_t>(sum) << 16) / weight;
    log_mean = Log2Sixteenths64(mean == 0 ? 1 : mean);
  } else {
    const EqUint128 mean = (sum << 16) / weight;
    log_mean = Log2Sixteenths(mean);
  }
  const int32_t s = log_mean - 16 * 16;
  *log_sigma2 = std::clamp(s, kEqMinLogSigma2, kEqMaxLogSigma2);
  return true;
}

EqQuantizer SelectQuantizer(int shape, int32_t log_sigma2, int32_t lambda_code) {
  const int32_t s = std::clamp(log_sigma2, kEqMinLogSigma2, kEqMaxLogSigma2);
  EqQuantizer q;
  q.entry = &GetQuantizer(shape, QuantizerBucket(static_cast<int64_t>(lambda_code) + s));
  q.sigma_q16 = SigmaQ16(s);
  if (q.sigma_q16 == 0) q.entry = &GetQuantizer(shape, -1);
  return q;
}

int64_t ReconstructIndex(const EqQuantizer& quantizer, int64_t q) {
  if (q == 0 || quantizer.codes_nothing()) return 0;
  const int64_t mag = q < 0 ? -q : q;
  const EqInt128 product =
      static_cast<EqInt128>(quantizer.sigma_q16) * quantizer.entry->ReconstructionQ16(mag);
  const EqInt128 rounded = (product + (static_cast<EqInt128>(1) << 31)) >> 32;
  const int64_t value = rounded > kEqMaxCoefficient ? kEqMaxCoefficient : static_cast<int64_t>(rounded);
  return q < 0 ? -value : value;
}

EqChoice ChooseQuantizer(const EqSideInfo& side, const int64_t* recon, const EqContextTerms& terms,
                         size_t p) {
  int32_t log_sigma2_hat = 0;
  const bool predictable = EstimateLogSigma2(recon, terms, p, &log_sigma2_hat);
  return ChooseForEstimate(side, terms.tangential(), predictable, log_sigma2_hat);
}

EqChoice ChooseForEstimate(const EqSideInfo& side, bool t, bool predictable, int32_t log_sigma2_hat) {
  EqChoice c;
  c.log_sigma2_hat = log_sigma2_hat;
  if (predictable) {
    const EqGgdClass& cls = side.PredictableOf(t);
    const int32_t lambda_code = t ? side.lambda_code + side.tangential_code : side.lambda_code;
    c.ctx = t ? EqContext::kTangentialPredictable : EqContext::kPredictable;
    if (cls.present) c.quantizer = SelectQuantizer(cls.shape, log_sigma2_hat + cls.log_sigma2, lambda_code);
    return c;
  }
  c.ctx = t ? EqContext::kTangential : EqContext::kUnpredictable;
  c.quantizer = UnpredictableQuantizer(side, t);
  return c;
}

EqQuantizer UnpredictableQuantizer(const EqSideInfo& side, bool tangential) {
  const EqGgdClass& unpredictable = side.UnpredictableOf(tangential);
  if (!unpredictable.present) return {};
  const int32_t lambda_code = tangential ? side.lambda_code + side.tangential_code : side.lambda_code;
  return SelectQuantizer(unpredictable.shape, unpredictable.log_sigma2, lambda_code);
}

EqQuantizer TangentialQuantizer(const EqSideInfo& side) { return UnpredictableQuantizer(side, true); }

int EscapeOrder(const QuantizerEntry& entry) {
  int log2_step = 0;
  while (log2_step < 31 && (entry.step_q16 >> (log2_step + 1)) != 0) ++log2_step;
  return std::max(0, 15 - log2_step);
}

int64_t DecodeIndex(RangeDecoder* dec, const EqQuantizer& quantizer, EqContext ctx,
                    EqEscapeModels* models) {
  if (quantizer.codes_nothing()) return 0;
  const QuantizerEntry& e = *quantizer.entry;
  const uint32_t v = dec->DecodeFreq(kQuantizerFreqBits);
  uint32_t cum = 0;
  int m = 0;
  while (m < e.max_index && v >= cum + e.freq[m]) cum += e.freq[m++];
  dec->Consume(cum, e.freq[m]);
  if (m == 0) return 0;
  const bool negative = dec->DecodeBits(1) != 0;
  int64_t mag = m;
  if (m == e.max_index) {
    auto& prefix = models->prefix[static_cast<int>(ctx)];
    int p = 0;
    while (dec->DecodeBit(&prefix[p]) != 0) {
      if (++p > kEqMaxEscapePrefix || !dec->ok()) {
        dec->SetError();
        return 0;
      }
    }
    const int k = EscapeOrder(e);
    const int bits = p + k;  // <= 24 + 11: may exceed one 32-bit read
    uint64_t suffix = bits > 32 ? static_cast<uint64_t>(dec->DecodeBits(bits - 32)) << 32 : 0;
    suffix |= dec->DecodeBits(bits > 32 ? 32 : bits);
    mag += (int64_t{1} << bits) - (int64_t{1} << k) + static_cast<int64_t>(suffix);
  }
  return negative ? -mag : mag;
}

bool DecodeSideInfo(RangeDecoder* dec, uint32_t expected_count, bool tangential_context,
                    EqSideInfo* side) {
  const uint32_t count = dec->DecodeBits(32);
  ReadSigned(dec, kEqCodeBits, &side->lambda_code);
  ReadSigned(dec, kEqCodeBits, &side->tangential_code);
  bool ok = DecodeClass(dec, -kEqMaxGain, kEqMaxGain, &side->predictable);
  ok = DecodeClass(dec, kEqMinLogSigma2, kEqMaxLogSigma2, &side->unpredictable) && ok;
  ok = DecodeClass(dec, kEqMinLogSigma2, kEqMaxLogSigma2, &side->tangential) && ok;
  side->tangential_context = tangential_context;
  if (tangential_context) {
    ok = DecodeClass(dec, -kEqMaxGain, kEqMaxGain, &side->tangential_predictable) && ok;
  }
  return ok && dec->ok() && count == expected_count;
}

}  // namespace eqmesh

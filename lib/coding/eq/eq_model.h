// The part of the EQ coder (LoPresto, Ramchandran, Orchard, DCC 1997; Lavu, Choi,
// Baraniuk, SGP 2003, Sec. 3) that encoder and decoder must evaluate identically:
// side information, the causal sigma estimate, quantizer selection, reconstruction
// and symbol (de)coding. Integer / fixed-point only, so both sides select the same
// quantizer on any compiler.
//
// Units: every coefficient is an integer multiple of the stream quantum q0 once
// reconstructed. Sigmas and lambda travel as base-2 logarithms in 1/16 octave:
//   lambda * q0^2        = 2^(lambda_code / 16)        (D measured in q0^2)
//   sigma^2 / q0^2       = 2^(log_sigma2 / 16)
//
// Normative per-coefficient rules (both halves call these functions):
//  * sigma-hat^2 of a normal coefficient: S = sum w r^2 over its causal neighbours
//    (r their reconstructions in q0, w = 4, 2, 1 for rings 1, 2, 3), W = sum w;
//    log_sigma2_hat = Log2Sixteenths(max(1, floor(S 2^16 / W))) - 256, clamped to
//    [kEqMinLogSigma2, kEqMaxLogSigma2]; S = 0 (or no neighbour) -> unpredictable.
//  * predictable: s = log_sigma2_hat + gain; unpredictable / tangential: s = the
//    class's log_sigma2. Quantizer = table entry (class shape,
//    QuantizerBucket(lambda_code [+ tangential_code] + s)), scaled by
//    sigma_q16 = round(2^30 2^((s mod 32) / 32)) shifted by floor(s / 32) - 14.
//  * reconstruction of index q != 0: sign(q) min(2^28, floor((sigma_q16 *
//    ReconstructionQ16(|q|) + 2^31) / 2^32)) quanta.
//  * tangential components (stream 1.3, EqSideInfo::tangential_context): the same
//    estimate over the tangential stream, value 2i + c = component c (0 tangent, 1
//    bitangent) of scan position i. Its terms are both tangential components of
//    every causal neighbour (weights 4, 2, 1 by ring) and, for the bitangent, the
//    vertex's own tangent (weight 4); all zero -> the unpredictable tangential class
//    (`tangential`), else sigma-hat times the tangential gain, at lambda_code +
//    tangential_code. Streams 1.0-1.2 code every tangential component with the one
//    class `tangential`.
//  * chunk: side information, then the normal index of every vertex in scan order,
//    then (tangent, bitangent) indices vertex by vertex in scan order. An index is
//    the magnitude symbol min(|q|, M) under the entry's frequencies (total 2^15), a
//    bypass sign bit if non-zero, and the escape when |q| >= M. A class or entry that
//    codes nothing writes no bits.
//
// Departures from the papers:
//  * sigma-hat is the ring-weighted RMS of the reconstructed causal neighbours
//    (weights 4, 2, 1 for rings 1, 2, 3) times a per-level gain sent as side
//    information, rather than the ML estimate under the GGD: the RMS is exact in
//    integers, and the gain absorbs its bias for the level's actual distribution.
//  * A coefficient is unpredictable exactly when its causal neighbours all
//    reconstruct to zero (or it has none), which the decoder can check itself.
//  * The seed codes tangential components as iid per level. They are not: the
//    non-normal vertices (a few percent) carry nearly all tangential energy, and
//    they cluster (holes, creases, wherever piercing failed). So 1.3 streams give
//    the tangential components the EQ treatment too: a spatial context and their
//    own predictable / unpredictable classes (1-3 % fewer bytes at 1-2 bpv;
//    measured: bench/log/2026-12-05-codec-notebook.md).
//  * Magnitudes at or beyond the table's open bin M are escaped with an adaptive
//    Exp-Golomb code of |q| - M (context-modelled prefix, bypass suffix) whose order
//    k = max(0, 15 - floor(log2 step_q16)) puts 2^k near half a sigma in steps, so
//    the prefix statistics hardly depend on the step and one model set per class
//    serves every bucket.
#pragma once

#include <array>
#include <cstdint>

#include "coding/entropy/quantizer_table.h"
#include "coding/entropy/range_coder.h"
#include "coding/eq/eq_layout.h"

namespace eqmesh {

// Reconstructed coefficients are clamped to this many q0 (both sides).
inline constexpr int64_t kEqMaxCoefficient = int64_t{1} << 28;
// Escape prefix limit: |q| - M < 2^(kEqMaxEscapePrefix + 1 + order) - 2^order.
inline constexpr int kEqMaxEscapePrefix = 24;
// Log-sigma codes are kept inside this range (sigma from 2^-20 to 2^30 q0).
inline constexpr int32_t kEqMinLogSigma2 = -640;
inline constexpr int32_t kEqMaxLogSigma2 = 960;

// One GGD class of a level: its shape (table index) and sigma. `present` false
// means the class codes nothing (all its coefficients reconstruct to zero).
struct EqGgdClass {
  bool present = false;
  uint8_t shape = 5;         // index into the table's shapes (nu = 0.5 + 0.1 shape)
  int32_t log_sigma2 = 0;    // for predictable coefficients: the gain over sigma-hat^2
};

// Side information of one level, sent at the start of its chunk.
struct EqSideInfo {
  int32_t lambda_code = 0;
  int32_t tangential_code = 0;  // lambda_t = lambda * 2^(tangential_code / 16)
  EqGgdClass predictable;       // log_sigma2 is the gain g: sigma^2 = sigma_hat^2 2^(g/16)
  EqGgdClass unpredictable;
  EqGgdClass tangential;        // all tangential components, or (1.3) the unpredictable ones
  // Stream 1.3: tangential components are context-modelled; this is their gain.
  bool tangential_context = false;
  EqGgdClass tangential_predictable;

  // The two classes of a context-modelled stream: the normal one, or (1.3) the
  // tangential one.
  const EqGgdClass& PredictableOf(bool tangential_stream) const {
    return tangential_stream ? tangential_predictable : predictable;
  }
  const EqGgdClass& UnpredictableOf(bool tangential_stream) const {
    return tangential_stream ? tangential : unpredictable;
  }
  EqGgdClass* MutablePredictableOf(bool tangential_stream) {
    return tangential_stream ? &tangential_predictable : &predictable;
  }
  EqGgdClass* MutableUnpredictableOf(bool tangential_stream) {
    return tangential_stream ? &tangential : &unpredictable;
  }
};

__extension__ typedef unsigned __int128 EqUint128;  // GCC/Clang; pedantic-clean
__extension__ typedef __int128 EqInt128;

// floor(16 * log2(x)) for x >= 1, exactly, in integers.
int32_t Log2Sixteenths(EqUint128 x);

// Which reconstructed values (and with which weights) feed the sigma estimate of
// value p of one of a level's two coded streams: the normal stream (p = scan
// position) or the tangential stream (p = 2 scan position + component).
class EqContextTerms {
 public:
  EqContextTerms(const EqLevelLayout& layout, bool tangential)
      : layout_(layout), tangential_(tangential) {}
  bool tangential() const { return tangential_; }
  size_t size() const { return tangential_ ? 2 * layout_.size() : layout_.size(); }

  // Calls f(value index, weight) for every term of value p.
  template <typename F>
  void ForEach(size_t p, F&& f) const {
    const size_t i = tangential_ ? p / 2 : p;
    for (uint32_t e = layout_.offsets[i]; e < layout_.offsets[i + 1]; ++e) {
      const uint32_t w = 4u >> (layout_.ring[e] - 1);
      const uint32_t n = layout_.neighbours[e];
      if (!tangential_) {
        f(n, w);
        continue;
      }
      f(2 * size_t{n}, w);
      f(2 * size_t{n} + 1, w);
    }
    if (tangential_ && (p & 1) != 0) f(p - 1, 4u);
  }

 private:
  const EqLevelLayout& layout_;
  bool tangential_;
};

// log2(sigma_hat^2) in 1/16 octave from the reconstructed terms of value p (recon in
// q0, indexed like the stream); false when every term is zero or there is none (the
// value is unpredictable).
bool EstimateLogSigma2(const int64_t* recon, const EqContextTerms& terms, size_t p,
                       int32_t* log_sigma2);

// The quantizer of one coefficient: a table entry and the sigma it is scaled by.
struct EqQuantizer {
  const QuantizerEntry* entry = nullptr;
  int64_t sigma_q16 = 0;  // sigma in q0 units, Q16
  bool codes_nothing() const { return entry == nullptr || entry->codes_nothing(); }
};
EqQuantizer SelectQuantizer(int shape, int32_t log_sigma2, int32_t lambda_code);

// Reconstruction of index q (in q0 units, clamped to kEqMaxCoefficient).
int64_t ReconstructIndex(const EqQuantizer& quantizer, int64_t q);

// Context sets of the escape models.
enum class EqContext : int {
  kPredictable = 0,
  kUnpredictable = 1,
  kTangential = 2,  // the tangential class: all of them (1.0-1.2) or the unpredictable ones
  kTangentialPredictable = 3,
};
struct EqEscapeModels {
  std::array<std::array<AdaptiveBit, kEqMaxEscapePrefix + 1>, 4> prefix;
};

// The quantizer of value p of a context-modelled stream (the normal stream, or the
// 1.3 tangential one) from its terms (recon indexed like the stream): predictable
// values use sigma-hat times the stream's gain and its predictable shape; the rest
// use the stream's unpredictable class.
struct EqChoice {
  EqQuantizer quantizer;
  EqContext ctx = EqContext::kUnpredictable;
  int32_t log_sigma2_hat = 0;  // sigma-hat^2 before the gain (predictable only)
};
EqChoice ChooseQuantizer(const EqSideInfo& side, const int64_t* recon, const EqContextTerms& terms,
                         size_t p);
// The same choice from the estimate's outcome: whether the neighbourhood gave a
// sigma-hat (`predictable`) and, if so, its log_sigma2_hat. An encoder that kept
// a pass's partition chooses again from it without the neighbours.
EqChoice ChooseForEstimate(const EqSideInfo& side, bool tangential, bool predictable, int32_t log_sigma2_hat);
// Streams 1.0-1.2: the one quantizer of every tangential component.
EqQuantizer TangentialQuantizer(const EqSideInfo& side);
// The quantizer of a value whose causal neighbourhood is all zero (of the
// tangential stream, or of the normal one). When it codes nothing for both
// streams, every value of the level is zero: the first value of each stream has
// no neighbours, and by induction each later one sees only zeros.
EqQuantizer UnpredictableQuantizer(const EqSideInfo& side, bool tangential);

// Exp-Golomb order of the escape of an entry (see above).
int EscapeOrder(const QuantizerEntry& entry);

// Decodes one index; the decoder's error flag reports impossible streams.
int64_t DecodeIndex(RangeDecoder* dec, const EqQuantizer& quantizer, EqContext ctx,
                    EqEscapeModels* models);

// Side information layout (bypass bits, in this order): coefficient count (32),
// lambda_code and tangential_code (16 each, offset 2^15), then per class
// (predictable, unpredictable, tangential, and with tangential_context the
// tangential predictable one): present (1), and if present shape (4) and
// log_sigma2 (12, offset 2^11). Decoding validates every range.
inline constexpr int32_t kEqMaxGain = 1024;  // |predictable gain| limit
bool DecodeSideInfo(RangeDecoder* dec, uint32_t expected_count, bool tangential_context,
                    EqSideInfo* side);

// Bits of the side-information fields, shared by both halves.
inline constexpr int kEqCodeBits = 16;
inline constexpr int kEqLogBits = 12;
inline constexpr int kEqShapeBits = 4;

}  // namespace eqmesh

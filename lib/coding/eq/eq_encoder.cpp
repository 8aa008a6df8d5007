// EQ level encoder: see eq_encoder.h for the papers followed and the departures.
#include "coding/eq/eq_encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "coding/entropy/ggd.h"
#include "coding/entropy/range_coder.h"
#include "core/parallel_for.h"

namespace eqmesh {
namespace {

// Fewest coefficients for which a level's two streams iterate on two threads:
// starting a thread costs tens of microseconds, too much for the coarse levels.
constexpr size_t kSideBySideStreams = 4096;

// Largest excess every entry can escape (order 0 is the tightest).
constexpr int64_t kMaxEscapeExcess = (int64_t{1} << (kEqMaxEscapePrefix + 1)) - 2;

int32_t ClampLog(double v, int32_t lo, int32_t hi) {
  if (!(v > lo)) return lo;
  if (!(v < hi)) return hi;
  return static_cast<int32_t>(std::lround(v));
}

// Maximum-likelihood GGD fit over the table's shapes (LoPresto et al. 1997): for a
// shape nu the ML sigma is sigma^nu = (nu / N) eta1^nu sum |x|^nu with
// eta1 = sqrt(Gamma(3/nu) / Gamma(1/nu)), and then sum (eta |x|)^nu = N / nu, so the
// negative log-likelihood per sample is -log(nu eta1 / (2 sigma Gamma(1/nu))) + 1/nu.
// Heavy-tailed samples get small shapes instead of an inflated sigma.
class GgdFit {
 public:
  void Add(double x) { values_.push_back(std::fabs(x)); }

  EqGgdClass ToClass(int32_t lo, int32_t hi) const {
    EqGgdClass c;
    double max_abs = 0;
    for (double v : values_) max_abs = std::max(max_abs, v);
    if (values_.empty() || max_abs == 0) return c;
    const double n = static_cast<double>(values_.size());
    const std::array<double, kQuantizerShapeCount> sums = ScaledPowerSums(max_abs);
    double best_nll = 0, best_log_sigma = 0;
    for (int s = 0; s < kQuantizerShapeCount; ++s) {
      const double nu = QuantizerTableLayout::Shape(s);
      const double lg1 = std::lgamma(1.0 / nu);
      const double log_eta1 = 0.5 * (std::lgamma(3.0 / nu) - lg1);
      const double log_sigma = std::log(max_abs) + std::log(nu / n * sums[s]) / nu + log_eta1;
      const double nll = -(std::log(nu / 2.0) + log_eta1 - log_sigma - lg1) + 1.0 / nu;
      if (s == 0 || nll < best_nll) {
        best_nll = nll;
        best_log_sigma = log_sigma;
        c.shape = static_cast<uint8_t>(s);
      }
    }
    c.present = true;
    c.log_sigma2 = ClampLog(32.0 * best_log_sigma / std::log(2.0), lo, hi);
    return c;
  }

 private:
  // sum over the values of (|x| / max_abs)^nu for every table shape (scaled against
  // overflow). The shapes are nu = 0.5 + 0.1 s, so the terms are sqrt(t) (t^0.1)^s:
  // one pow per value instead of one per value and shape, which would be a third
  // of the encoder's time (bunny, --bpv 1).
  std::array<double, kQuantizerShapeCount> ScaledPowerSums(double max_abs) const {
    std::array<double, kQuantizerShapeCount> sums{};
    for (double v : values_) {
      if (v == 0) continue;
      const double t = v / max_abs;
      const double ratio = std::pow(t, 0.1);
      double term = std::sqrt(t);
      for (double& sum : sums) {
        sum += term;
        term *= ratio;
      }
    }
    return sums;
  }

  std::vector<double> values_;
};

// Estimated bits of index q under an entry (frequency, sign, escape).
double IndexBits(const QuantizerEntry& e, int64_t q) {
  const int64_t mag = q < 0 ? -q : q;
  const int slot = static_cast<int>(std::min<int64_t>(mag, e.max_index));
  double bits = kQuantizerFreqBits - std::log2(static_cast<double>(e.freq[slot]));
  if (mag > 0) bits += 1;
  if (mag >= e.max_index) {
    const int k = EscapeOrder(e);
    const double v = static_cast<double>(mag - e.max_index) / std::exp2(k) + 1.0;
    bits += 2 * std::floor(std::log2(v)) + 1 + k;
  }
  return bits;
}

// Index of {0, k-1, k} minimising bits + lambda (x - recon)^2, k the dead-zone index.
int64_t ChooseIndex(double x, const EqQuantizer& quantizer, double lambda_q0) {
  if (quantizer.codes_nothing()) return 0;
  const QuantizerEntry& e = *quantizer.entry;
  const double sigma = static_cast<double>(quantizer.sigma_q16) / 65536.0;
  const double u = std::fabs(x) / sigma;
  const double z = e.dead_zone_q16 / 65536.0, step = e.step_q16 / 65536.0;
  const double limit = static_cast<double>(e.max_index + kMaxEscapeExcess);
  const int64_t k = u <= z ? 0 : static_cast<int64_t>(std::min(std::ceil((u - z) / step), limit));
  const int64_t sign = x < 0 ? -1 : 1;
  int64_t best = 0;
  double best_j = 0;
  for (int64_t c : {int64_t{0}, k - 1, k}) {
    if (c < 0 || (c == 0 && best_j != 0)) continue;
    const double err = x - static_cast<double>(ReconstructIndex(quantizer, sign * c));
    const double j = IndexBits(e, c) + lambda_q0 * err * err;
    if (c == 0 || j < best_j) {
      best = c;
      best_j = j;
    }
  }
  return sign * best;
}

void EncodeIndex(RangeEncoder* enc, const EqQuantizer& quantizer, int64_t q, EqContext ctx,
                 EqEscapeModels* models) {
  if (quantizer.codes_nothing()) return;
  const QuantizerEntry& e = *quantizer.entry;
  const int64_t mag = q < 0 ? -q : q;
  const int m = static_cast<int>(std::min<int64_t>(mag, e.max_index));
  uint32_t cum = 0;
  for (int s = 0; s < m; ++s) cum += e.freq[s];
  enc->EncodeSymbol(cum, e.freq[m], kQuantizerFreqBits);
  if (m == 0) return;
  enc->EncodeBits(q < 0 ? 1u : 0u, 1);
  if (m < e.max_index) return;
  // Order-k Exp-Golomb of the excess: p ones on adaptive prefix models, a zero,
  // then p + k bypass bits.
  const int k = EscapeOrder(e);
  const uint64_t v = static_cast<uint64_t>(mag - e.max_index) + (uint64_t{1} << k);
  int p = 0;
  while ((v >> (p + k + 1)) != 0) ++p;
  auto& prefix = models->prefix[static_cast<int>(ctx)];
  for (int i = 0; i < p; ++i) enc->EncodeBit(&prefix[i], 1);
  enc->EncodeBit(&prefix[p], 0);
  const int bits = p + k;  // <= 24 + 11: may exceed one 32-bit write
  const uint64_t suffix = v - (uint64_t{1} << bits);
  if (bits > 32) enc->EncodeBits(static_cast<uint32_t>(suffix >> 32), bits - 32);
  enc->EncodeBits(static_cast<uint32_t>(suffix & 0xFFFFFFFFu), bits > 32 ? 32 : bits);
}

void EncodeClass(RangeEncoder* enc, const EqGgdClass& c) {
  enc->EncodeBits(c.present ? 1u : 0u, 1);
  if (!c.present) return;
  enc->EncodeBits(c.shape, kEqShapeBits);
  enc->EncodeBits(static_cast<uint32_t>(c.log_sigma2 + (1 << (kEqLogBits - 1))), kEqLogBits);
}

void EncodeSideInfo(RangeEncoder* enc, const EqSideInfo& side, uint32_t count) {
  enc->EncodeBits(count, 32);
  enc->EncodeBits(static_cast<uint32_t>(side.lambda_code + (1 << (kEqCodeBits - 1))), kEqCodeBits);
  enc->EncodeBits(static_cast<uint32_t>(side.tangential_code + (1 << (kEqCodeBits - 1))), kEqCodeBits);
  EncodeClass(enc, side.predictable);
  EncodeClass(enc, side.unpredictable);
  EncodeClass(enc, side.tangential);
  if (side.tangential_context) EncodeClass(enc, side.tangential_predictable);
}

// Per stream position: the partition and sigma-hat a pass produced.
struct Partition {
  std::vector<uint8_t> predictable;
  std::vector<int32_t> log_sigma2_hat;
};

// A causal pass over one stream under one side information: its partition (with
// it and the side information, ChooseForEstimate gives each value's quantizer
// again), its reconstruction and its indices. Coding them is what a pass with an
// encoder would code: the choices depend on the side information and the values alone.
struct PassResult {
  Partition partition;
  std::vector<int64_t> recon;
  std::vector<int64_t> indices;
};

// One context-modelled stream of a level (normal values by scan position, or the
// 1.3 tangential values 2i + c) and its lambda.
class StreamEncoder {
 public:
  StreamEncoder(const EqContextTerms& terms, std::vector<double> values, double lambda_q0)
      : terms_(terms), values_(std::move(values)), lambda_q0_(lambda_q0) {}

  const std::vector<double>& values() const { return values_; }

  // Step 6: threshold the unquantized terms.
  Partition InitialPartition() const {
    const double threshold = 0.5 * std::sqrt(6.0 / (lambda_q0_ * std::log(2.0)));
    Partition p;
    p.predictable.assign(values_.size(), 0);
    p.log_sigma2_hat.assign(values_.size(), 0);
    for (size_t i = 0; i < values_.size(); ++i) {
      double sum = 0, weight = 0;
      bool significant = false;
      terms_.ForEach(i, [&](size_t n, uint32_t w) {
        const double x = values_[n];
        sum += w * x * x;
        weight += w;
        significant = significant || std::fabs(x) >= threshold;
      });
      if (!significant) continue;
      p.predictable[i] = 1;
      p.log_sigma2_hat[i] = ClampLog(16.0 * std::log2(sum / weight), kEqMinLogSigma2, kEqMaxLogSigma2);
    }
    return p;
  }

  // Step 8: GGD parameters of the two classes of a partition.
  void EstimateClasses(const Partition& p, EqSideInfo* side) const {
    GgdFit pred, unpred;
    for (size_t i = 0; i < values_.size(); ++i) {
      if (p.predictable[i]) {
        pred.Add(values_[i] / std::exp2(p.log_sigma2_hat[i] / 32.0));
      } else {
        unpred.Add(values_[i]);
      }
    }
    EqGgdClass* predictable = side->MutablePredictableOf(terms_.tangential());
    *predictable = pred.ToClass(-kEqMaxGain, kEqMaxGain);
    // A predictable class with nothing in it still needs a quantizer should the
    // pass under it classify differently: keep it present with unit gain.
    if (!predictable->present) *predictable = {true, 5, 0};
    *side->MutableUnpredictableOf(terms_.tangential()) = unpred.ToClass(kEqMinLogSigma2, kEqMaxLogSigma2);
  }

  // Steps 9-14: one causal pass (into *out, whose buffers it reuses); returns
  // the estimated cost sum (bits + lambda err^2).
  double Pass(const EqSideInfo& side, PassResult* out) const {
    const size_t n = values_.size();
    Partition& p = out->partition;
    p.predictable.assign(n, 0);
    p.log_sigma2_hat.assign(n, 0);
    out->recon.assign(n, 0);
    out->indices.resize(n);
    double cost = 0;
    for (size_t i = 0; i < n; ++i) {
      const EqChoice c = ChooseQuantizer(side, out->recon.data(), terms_, i);
      p.predictable[i] = c.ctx == EqContext::kPredictable || c.ctx == EqContext::kTangentialPredictable;
      p.log_sigma2_hat[i] = c.log_sigma2_hat;
      const int64_t q = ChooseIndex(values_[i], c.quantizer, lambda_q0_);
      out->indices[i] = q;
      out->recon[i] = ReconstructIndex(c.quantizer, q);
      const double err = values_[i] - static_cast<double>(out->recon[i]);
      cost += lambda_q0_ * err * err + (c.quantizer.codes_nothing() ? 0.0 : IndexBits(*c.quantizer.entry, q));
    }
    return cost;
  }

 private:
  const EqContextTerms& terms_;
  std::vector<double> values_;  // by stream position, in q0
  double lambda_q0_;
};

// Steps 5-16: alternate parameter estimation and causal passes until the partition
// the parameters were estimated from reproduces itself (or repeats: a cycle).
// Returns the side information of lowest estimated cost among those tried, with
// its pass (*best), so the stream is coded from that pass instead of a pass of
// its own: the choices are the same.
EqSideInfo IterateClasses(const StreamEncoder& stream, EqSideInfo side, int max_iterations, PassResult* best,
                          EqEncodeStats* stats) {
  const Partition initial = stream.InitialPartition();
  // The classes of every partition so far, to see one come back.
  std::vector<std::vector<uint8_t>> history = {initial.predictable};
  const Partition* last = &initial;
  PassResult pass;
  EqSideInfo best_side = side;
  double best_cost = 0;
  for (int it = 0; it < std::max(1, max_iterations); ++it) {
    stream.EstimateClasses(*last, &side);
    const double cost = stream.Pass(side, &pass);
    const bool improved = it == 0 || cost < best_cost;
    if (improved) {
      best_cost = cost;
      best_side = side;
      std::swap(*best, pass);
    }
    const Partition& next = improved ? best->partition : pass.partition;
    if (stats != nullptr) {
      stats->iterations = it + 1;
      stats->last_change = 0;
      for (size_t i = 0; i < next.predictable.size(); ++i) {
        stats->last_change += next.predictable[i] != history.back()[i];
      }
    }
    const auto seen = std::find(history.begin(), history.end(), next.predictable);
    if (seen == history.end() - 1) {
      if (stats != nullptr) stats->converged = true;
      break;
    }
    if (seen != history.end()) {
      if (stats != nullptr) stats->cycle_length = static_cast<int>(history.end() - seen);
      break;
    }
    history.push_back(next.predictable);
    last = &next;
  }
  return best_side;
}

// Codes a stream as its pass under `side` chose.
void CodePass(const EqSideInfo& side, bool tangential, const PassResult& pass, RangeEncoder* enc,
              EqEscapeModels* models) {
  const Partition& p = pass.partition;
  for (size_t i = 0; i < pass.indices.size(); ++i) {
    const EqChoice c = ChooseForEstimate(side, tangential, p.predictable[i] != 0, p.log_sigma2_hat[i]);
    EncodeIndex(enc, c.quantizer, pass.indices[i], c.ctx, models);
  }
}

// Streams 1.0-1.2: every tangential component with the one iid class.
std::vector<int64_t> CodeIidTangential(const EqSideInfo& side, const std::vector<double>& values,
                                       double lambda_t, RangeEncoder* enc, EqEscapeModels* models) {
  const EqQuantizer tq = TangentialQuantizer(side);
  std::vector<int64_t> recon(values.size());
  for (size_t p = 0; p < values.size(); ++p) {
    const int64_t q = ChooseIndex(values[p], tq, lambda_t);
    EncodeIndex(enc, tq, q, EqContext::kTangential, models);
    recon[p] = ReconstructIndex(tq, q);
  }
  return recon;
}

Status ValidateInputs(const EqLevelLayout& layout, const std::vector<Vec3>& coeffs, double q0,
                      const EqEncodeOptions& options) {
  const std::string where = "EQ level " + std::to_string(layout.level);
  if (coeffs.size() != layout.size()) {
    return InvalidArgument(where + ": " + std::to_string(coeffs.size()) + " coefficients for " +
                           std::to_string(layout.size()) + " odd vertices");
  }
  if (!(q0 > 0) || !std::isfinite(q0)) return InvalidArgument(where + ": quantum q0 must be positive");
  if (!(options.tangential_lambda_scale > 0) || !std::isfinite(options.tangential_lambda_scale)) {
    return InvalidArgument(where + ": tangential factor must be positive");
  }
  const int32_t code_limit = 1 << (kEqCodeBits - 1);
  if (options.lambda_code < -code_limit || options.lambda_code >= code_limit) {
    return InvalidArgument(where + ": lambda code out of range");
  }
  const double limit = static_cast<double>(kEqMaxCoefficient / 2) * q0;
  for (size_t k = 0; k < coeffs.size(); ++k) {
    if (!coeffs[k].allFinite() || coeffs[k].cwiseAbs().maxCoeff() > limit) {
      return InvalidArgument(where + ": coefficient " + std::to_string(k) +
                             " is not finite or exceeds 2^27 quanta (q0 too small)");
    }
  }
  return Status::Ok();
}

}  // namespace

int32_t EqLambdaCode(double lambda, double q0) {
  const int32_t limit = 1 << (kEqCodeBits - 1);
  return ClampLog(16.0 * std::log2(lambda * q0 * q0), -limit, limit - 1);
}

StatusOr<std::vector<uint8_t>> EncodeEqLevel(const EqLevelLayout& layout,
                                             const std::vector<Vec3>& local_coeffs, double q0,
                                             const EqEncodeOptions& options,
                                             std::vector<Vec3>* reconstructed,
                                             EqEncodeStats* stats) {
  EQMESH_RETURN_IF_ERROR(ValidateInputs(layout, local_coeffs, q0, options));
  const size_t n = layout.size();
  std::vector<double> normal(n), tangential(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3& c = local_coeffs[layout.scan[i]];
    normal[i] = c[0] / q0;
    tangential[2 * i] = c[1] / q0;
    tangential[2 * i + 1] = c[2] / q0;
  }
  EqSideInfo side;
  side.lambda_code = options.lambda_code;
  side.tangential_context = options.tangential_context;
  const int32_t code_limit = 1 << (kEqCodeBits - 1);
  side.tangential_code = ClampLog(16.0 * std::log2(options.tangential_lambda_scale), -code_limit, code_limit - 1);
  const double lambda_q0 = std::exp2(options.lambda_code / 16.0);
  const double lambda_t = lambda_q0 * std::exp2(side.tangential_code / 16.0);
  const EqContextTerms normal_terms(layout, false), tangential_terms(layout, true);
  const StreamEncoder normal_stream(normal_terms, std::move(normal), lambda_q0);
  const StreamEncoder tangential_stream(tangential_terms, std::move(tangential), lambda_t);
  EqEncodeStats local_stats;
  PassResult normal_pass, tangential_pass;
  EqSideInfo normal_side = side, tangential_side = side;
  // The two streams' iterations read and write disjoint parts of the side
  // information (eq_model.h: each stream's classes), so they run side by side.
  // Stream 0 is the normal one, 1 the tangential one.
  const auto iterate = [&](size_t stream) {
    if (stream == 0) {
      normal_side = IterateClasses(normal_stream, side, options.max_iterations, &normal_pass, &local_stats);
    } else if (side.tangential_context) {
      tangential_side = IterateClasses(tangential_stream, side, options.max_iterations, &tangential_pass, nullptr);
    }
  };
  if (side.tangential_context && n >= kSideBySideStreams) {
    ParallelFor(2, [&](size_t begin, size_t end, size_t) { for (size_t k = begin; k < end; ++k) iterate(k); }, 1);
  } else {
    iterate(0);
    iterate(1);
  }
  side = normal_side;
  if (side.tangential_context) {
    side.tangential = tangential_side.tangential;
    side.tangential_predictable = tangential_side.tangential_predictable;
  } else {
    GgdFit iid_tangential;
    for (double v : tangential_stream.values()) iid_tangential.Add(v);
    side.tangential = iid_tangential.ToClass(kEqMinLogSigma2, kEqMaxLogSigma2);
  }

  RangeEncoder enc;
  EncodeSideInfo(&enc, side, static_cast<uint32_t>(n));
  EqEscapeModels models;
  CodePass(side, false, normal_pass, &enc, &models);
  const Partition& partition = normal_pass.partition;
  const std::vector<int64_t>& recon = normal_pass.recon;
  std::vector<int64_t> recon_t;
  if (side.tangential_context) {
    CodePass(side, true, tangential_pass, &enc, &models);
    recon_t = std::move(tangential_pass.recon);
  } else {
    recon_t = CodeIidTangential(side, tangential_stream.values(), lambda_t, &enc, &models);
  }
  std::vector<Vec3> out(n);
  for (size_t i = 0; i < n; ++i) {
    out[layout.scan[i]] = Vec3(static_cast<double>(recon[i]), static_cast<double>(recon_t[2 * i]),
                               static_cast<double>(recon_t[2 * i + 1])) * q0;
    local_stats.unpredictable += partition.predictable[i] ? 0 : 1;
    local_stats.nonzero_normal += recon[i] != 0 ? 1 : 0;
  }
  local_stats.side = side;
  if (stats != nullptr) *stats = local_stats;
  if (reconstructed != nullptr) *reconstructed = std::move(out);
  return enc.Finish();
}

}  // namespace eqmesh

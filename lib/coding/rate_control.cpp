#include "coding/rate_control.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "coding/bitstream_shared.h"

namespace eqmesh {
namespace {

constexpr int kMaxEvaluations = 40;
constexpr int64_t kQualityResolution = 1;  // one code: ~4.4 % of lambda

// Evaluates codes, counting and clamping them to the header's range.
class Prober {
 public:
  Prober(const RateEvaluator& eval, RateSearchReport* report) : eval_(eval), report_(report) {}
  StatusOr<RatePoint> operator()(int64_t code) {
    if (report_) ++report_->evaluations;
    ++count_;
    return eval_(code);
  }
  bool exhausted() const { return count_ >= kMaxEvaluations; }

 private:
  const RateEvaluator& eval_;
  RateSearchReport* report_;
  int count_ = 0;
};

bool InRange(int64_t code) { return code >= -bitstream::kMaxLogCode && code <= bitstream::kMaxLogCode; }

// How a search steps toward its target before it has bracketed it: the
// quantity it reads off a point, the model's slope of that quantity per code,
// and the secant slopes (through the last two points) it trusts instead. A
// secant steeper than trusted says the quantity jumps there: the model steps
// better. A flatter one says it is saturating (every coefficient coded, or the
// stream near its level count's ceiling): steps of one octave of lambda then,
// doubling each time, so a flat stretch is crossed, or the code range's end
// reached, in a few evaluations.
// No `value` means no model: octave steps, doubling, all the way.
struct StepModel {
  double (*value)(const RatePoint&);
  double per_code;
  double min_secant, max_secant;
  int64_t first_limit;  // largest model step at first; it doubles after every step
};

double LogSize(const RatePoint& p) { return p.bpv > 0 ? std::log2(p.bpv) : -std::numeric_limits<double>::infinity(); }

// The rate model: 4x lambda (32 codes) roughly doubles an EQ stream; horse's
// 4- to 6-level streams measure 35-43 codes per doubling between 0.4 and 7 bpv.
// Its first step may span eight octaves of lambda, more than lies between 1/64
// (the default lambda) and any rate from 0.1 to 10 bpv on the bench meshes.
constexpr StepModel kRateModel{LogSize, 1.0 / 36.0, 1.0 / 160.0, 1.0 / 8.0, 128};
// The quality search steps by octaves of lambda, doubling, with no model: near
// a level count's ceiling PSNR barely moves with the code, and a step sized by
// a model lands short again and again, each a measured pass
// (bench/log/2026-12-06-encoder-passes.md).
constexpr StepModel kOctaveSteps{nullptr, 0.0, 0.0, 0.0, 0};

// Value change per code from the secant through two points where it is
// trusted; the model's where it is too steep or there is no previous point;
// zero where it is too flat or there is no model.
double SlopePerCode(const StepModel& model, const RatePoint* previous, const RatePoint& p) {
  if (model.value == nullptr) return 0.0;
  if (previous == nullptr) return model.per_code;
  const double a = model.value(*previous), b = model.value(p);
  if (!std::isfinite(a) || !std::isfinite(b)) return model.per_code;
  const double slope = (b - a) / static_cast<double>(p.lambda_code - previous->lambda_code);
  if (slope < model.min_secant) return slope < 0 ? model.per_code : 0.0;
  return slope <= model.max_secant ? slope : model.per_code;
}

constexpr int64_t kFlatStep = 16;  // one octave of lambda

// The code where the slope puts `target` from p, at least one code and at most
// `limit` codes away in direction `up`; `flat_step` codes away (then doubled)
// where the secant is too flat to say.
int64_t StepToward(const StepModel& model, const RatePoint* previous, const RatePoint& p, double target, bool up,
                   int64_t limit, int64_t* flat_step) {
  const double slope = SlopePerCode(model, previous, p);
  int64_t step = limit;
  if (slope == 0.0) {
    step = *flat_step;
    *flat_step *= 2;
  } else if (const double codes = std::abs((target - model.value(p)) / slope); std::isfinite(codes)) {
    const double bounded = std::min(codes, static_cast<double>(limit));
    step = std::clamp<int64_t>(std::llround(bounded), 1, limit);
  }
  return p.lambda_code + (up ? step : -step);
}

enum class BracketEnd { kBracketed, kFound, kRangeEnd };

// From `start`, steps by the model toward `target` (the model's value) until a
// point is `found` (returned in *hi) or lies across the target: lo < hi with
// pred(lo) false and pred(hi) true, pred monotone (false ... true) in the code.
// At the range's end or the evaluation cap the last point is in *lo and *hi.
template <typename Pred, typename Found>
StatusOr<BracketEnd> Bracket(Prober& probe, const StepModel& model, double target, const Pred& pred,
                             const Found& found, int64_t start, RatePoint* lo, RatePoint* hi) {
  EQMESH_ASSIGN_OR_RETURN(RatePoint p, probe(start));
  std::optional<RatePoint> previous;
  const bool up = !pred(p);
  int64_t flat_step = kFlatStep;
  for (int64_t limit = model.first_limit;; limit *= 2) {
    if (found(p)) {
      *hi = std::move(p);
      return BracketEnd::kFound;
    }
    const int64_t next = StepToward(model, previous ? &*previous : nullptr, p, target, up, limit, &flat_step);
    if (probe.exhausted() || !InRange(next)) break;
    EQMESH_ASSIGN_OR_RETURN(RatePoint q, probe(next));
    if (pred(q) == up && !found(q)) {
      *lo = up ? std::move(p) : std::move(q);
      *hi = up ? std::move(q) : std::move(p);
      return BracketEnd::kBracketed;
    }
    previous = std::move(p);
    p = std::move(q);
  }
  *lo = p;
  *hi = std::move(p);
  return BracketEnd::kRangeEnd;
}

}  // namespace

StatusOr<RatePoint> SearchForRate(const RateEvaluator& eval, double target_bpv, int64_t start_code,
                                  double rel_tolerance, RateSearchReport* report) {
  Prober probe(eval, report);
  std::optional<RatePoint> best;
  auto consider = [&](const RatePoint& p) {
    if (!best || std::abs(p.bpv - target_bpv) < std::abs(best->bpv - target_bpv)) best = p;
    return std::abs(p.bpv - target_bpv) <= rel_tolerance * target_bpv;
  };
  auto reaches = [&](const RatePoint& p) { return p.bpv >= target_bpv; };
  RatePoint lo, hi;
  EQMESH_ASSIGN_OR_RETURN(const BracketEnd end,
                          Bracket(probe, kRateModel, std::log2(target_bpv), reaches, consider, start_code, &lo, &hi));
  if (end == BracketEnd::kFound) return hi;
  if (end == BracketEnd::kRangeEnd) return *best;
  bool interpolate = true;
  while (hi.lambda_code - lo.lambda_code > 1 && !probe.exhausted()) {
    // log(bpv) is close to linear in the code: interpolate, but alternate with
    // bisection so a badly curved interval still shrinks geometrically.
    int64_t next = lo.lambda_code + (hi.lambda_code - lo.lambda_code) / 2;
    if (interpolate && lo.bpv > 0 && hi.bpv > lo.bpv) {
      const double t = (std::log(target_bpv) - std::log(lo.bpv)) / (std::log(hi.bpv) - std::log(lo.bpv));
      next = lo.lambda_code + std::llround(t * static_cast<double>(hi.lambda_code - lo.lambda_code));
      next = std::clamp(next, lo.lambda_code + 1, hi.lambda_code - 1);
    }
    interpolate = !interpolate;
    EQMESH_ASSIGN_OR_RETURN(RatePoint mid, probe(next));
    if (consider(mid)) return mid;
    (reaches(mid) ? hi : lo) = std::move(mid);
  }
  return *best;
}

namespace {

// Where the target falls between lo and hi, PSNR taken as linear in the code
// (clamped inside the interval); the middle when the two PSNRs cannot be
// interpolated (equal, out of order, or infinite).
int64_t InterpolatedCode(const RatePoint& lo, const RatePoint& hi, double target) {
  int64_t code = lo.lambda_code + (hi.lambda_code - lo.lambda_code) / 2;
  if (std::isfinite(lo.psnr_db) && std::isfinite(hi.psnr_db) && hi.psnr_db > lo.psnr_db) {
    const double t = (target - lo.psnr_db) / (hi.psnr_db - lo.psnr_db);
    code = lo.lambda_code + std::llround(t * static_cast<double>(hi.lambda_code - lo.lambda_code));
  }
  return std::clamp(code, lo.lambda_code + 1, hi.lambda_code - 1);
}

}  // namespace

StatusOr<RatePoint> SearchForQuality(const RateEvaluator& eval, double target_psnr,
                                     int64_t start_code, RateSearchReport* report) {
  Prober probe(eval, report);
  auto meets = [&](const RatePoint& p) { return p.psnr_db >= target_psnr; };
  RatePoint lo, hi;
  const auto never = [](const RatePoint&) { return false; };
  EQMESH_ASSIGN_OR_RETURN(const BracketEnd end,
                          Bracket(probe, kOctaveSteps, target_psnr, meets, never, start_code, &lo, &hi));
  if (end != BracketEnd::kBracketed) return hi;
  auto open = [&] { return hi.lambda_code - lo.lambda_code > kQualityResolution && !probe.exhausted(); };
  auto narrow = [&](int64_t code) -> Status {
    EQMESH_ASSIGN_OR_RETURN(RatePoint p, probe(code));
    (meets(p) ? hi : lo) = std::move(p);
    return Status::Ok();
  };
  // Every measured point costs a decode and a Metro measurement. PSNR is close to
  // linear in the code over a bracket, so a guess interpolated there is usually
  // within a code of the answer, and the guess's neighbour across the target then
  // closes the interval: two evaluations where bisecting a 16-code bracket takes
  // four. A bisection after each such pair keeps a badly curved interval
  // shrinking geometrically. Where quality is monotone in the code the answer is
  // the same code bisection finds.
  while (open()) {
    const int64_t guess = InterpolatedCode(lo, hi, target_psnr);
    EQMESH_RETURN_IF_ERROR(narrow(guess));
    if (!open()) break;
    EQMESH_RETURN_IF_ERROR(narrow(hi.lambda_code == guess ? guess - 1 : guess + 1));
    if (!open()) break;
    EQMESH_RETURN_IF_ERROR(narrow(lo.lambda_code + (hi.lambda_code - lo.lambda_code) / 2));
  }
  // Non-monotone corners: hi always meets the target; a smaller lo never returned.
  return hi;
}

namespace {

constexpr double kBudgetResolution = 1.01;

// Doubles (or halves) the budget until the target flips; false when the stream
// stops growing or the minimum is reached first (*best is then the answer).
StatusOr<bool> BracketBudget(const BudgetEvaluator& eval, double target, uint64_t start, uint64_t min_budget,
                             int* count, BudgetPoint* lo, BudgetPoint* hi) {
  EQMESH_ASSIGN_OR_RETURN(BudgetPoint p, eval(std::max(start, min_budget)));
  ++*count;
  const bool up = p.psnr_db < target;
  while (*count < kMaxEvaluations) {
    if (up && p.size < p.budget) break;        // complete stream: more bytes change nothing
    if (!up && p.budget <= min_budget) break;  // the smallest stream still meets it
    const uint64_t next = up ? p.budget * 2 : std::max(min_budget, p.budget / 2);
    EQMESH_ASSIGN_OR_RETURN(BudgetPoint q, eval(next));
    ++*count;
    if ((q.psnr_db < target) != up) {
      *lo = up ? p : q;
      *hi = up ? q : p;
      return true;
    }
    p = q;
  }
  *lo = p;
  *hi = p;
  return false;
}

}  // namespace

StatusOr<BudgetPoint> SearchBudgetForQuality(const BudgetEvaluator& eval, double target_psnr, uint64_t start,
                                             uint64_t min_budget, RateSearchReport* report) {
  int count = 0;
  BudgetPoint lo, hi;
  EQMESH_ASSIGN_OR_RETURN(const bool bracketed, BracketBudget(eval, target_psnr, start, min_budget, &count, &lo, &hi));
  while (bracketed && static_cast<double>(hi.budget) > kBudgetResolution * static_cast<double>(lo.budget) &&
         count < kMaxEvaluations) {
    const auto mid = static_cast<uint64_t>(std::sqrt(static_cast<double>(lo.budget) * static_cast<double>(hi.budget)));
    if (mid <= lo.budget || mid >= hi.budget) break;
    EQMESH_ASSIGN_OR_RETURN(BudgetPoint p, eval(mid));
    ++count;
    (p.psnr_db >= target_psnr ? hi : lo) = p;
  }
  if (report) report->evaluations = count;
  return hi;
}

}  // namespace eqmesh

#include "coding/rate_control.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "coding/bitstream_shared.h"

namespace eqmesh {
namespace {

constexpr int64_t kBracketStep = 16;  // one octave of lambda
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

// Finds lo < hi with pred(lo) false and pred(hi) true, by doubling steps from the
// start; pred must be monotone (false ... true) in the code. Returns false if the
// range ends first (the last point evaluated is then in *lo or *hi).
template <typename Pred>
StatusOr<bool> Bracket(Prober& probe, const Pred& pred, int64_t start, RatePoint* lo, RatePoint* hi) {
  EQMESH_ASSIGN_OR_RETURN(RatePoint p, probe(start));
  const bool up = !pred(p);
  int64_t step = kBracketStep;
  RatePoint prev = std::move(p);
  while (!probe.exhausted()) {
    const int64_t next = prev.lambda_code + (up ? step : -step);
    if (!InRange(next)) break;
    EQMESH_ASSIGN_OR_RETURN(RatePoint q, probe(next));
    if (pred(q) == up) {
      *lo = up ? std::move(prev) : std::move(q);
      *hi = up ? std::move(q) : std::move(prev);
      return true;
    }
    prev = std::move(q);
    step *= 2;
  }
  *lo = prev;
  *hi = std::move(prev);
  return false;
}

}  // namespace

namespace {

// Codes per doubling of the stream's size, the model the rate search steps by:
// 4x lambda (32 codes) roughly doubles an EQ stream; horse's 4- to 6-level
// streams measure 35-43 codes per doubling between 0.4 and 7 bpv.
constexpr double kCodesPerRateDoubling = 36.0;
// A secant through the last two points replaces the model where its slope
// (codes per doubling) is plausible. A steeper one says the size jumps there
// (most coefficients leaving the dead zone at once): the model steps better. A
// flatter one, or none, says the size is saturating (every coefficient coded):
// the step then follows the doubling schedule of its limit.
constexpr double kMinSecantCodes = 8.0;
constexpr double kMaxSecantCodes = 160.0;
// Largest first step: eight octaves of lambda, more than the model puts between
// 1/64 (the default lambda) and any rate from 0.1 to 10 bpv on the bench meshes;
// it doubles after each step that does not cross the target.
constexpr int64_t kFirstRateStepLimit = 128;

// Codes per doubling of the size from the secant through two points (infinite
// where the size did not grow), or the model's.
double CodesPerDoubling(const RatePoint* previous, const RatePoint& p) {
  if (previous == nullptr || !(previous->bpv > 0) || !(p.bpv > 0)) return kCodesPerRateDoubling;
  if (previous->bpv == p.bpv) return std::numeric_limits<double>::infinity();
  const double slope = static_cast<double>(p.lambda_code - previous->lambda_code) / std::log2(p.bpv / previous->bpv);
  if (slope > kMaxSecantCodes) return std::numeric_limits<double>::infinity();
  return slope >= kMinSecantCodes ? slope : kCodesPerRateDoubling;
}

// The code the size model puts the target at, from p, at least one code and at
// most `limit` codes away, in the direction of the target.
int64_t ModelStepToward(const RatePoint* previous, const RatePoint& p, double target, int64_t limit) {
  const bool up = p.bpv < target;
  double codes = static_cast<double>(limit);
  if (p.bpv > 0) codes = std::abs(CodesPerDoubling(previous, p) * std::log2(target / p.bpv));
  const int64_t step = std::clamp<int64_t>(std::llround(std::min(codes, static_cast<double>(limit))), 1, limit);
  return p.lambda_code + (up ? step : -step);
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
  // Bracket: step where the size model puts the target (a secant once two
  // points are known) until a point lands within tolerance or across the target.
  EQMESH_ASSIGN_OR_RETURN(RatePoint p, probe(start_code));
  if (consider(p)) return p;
  const bool up = !reaches(p);
  std::optional<RatePoint> previous;
  RatePoint lo, hi;
  bool bracketed = false;
  for (int64_t limit = kFirstRateStepLimit; !probe.exhausted(); limit *= 2) {
    const int64_t next = ModelStepToward(previous ? &*previous : nullptr, p, target_bpv, limit);
    if (!InRange(next)) break;
    EQMESH_ASSIGN_OR_RETURN(RatePoint q, probe(next));
    if (consider(q)) return q;
    if (reaches(q) == up) {
      lo = up ? std::move(p) : std::move(q);
      hi = up ? std::move(q) : std::move(p);
      bracketed = true;
      break;
    }
    previous = std::move(p);
    p = std::move(q);
  }
  if (!bracketed) return *best;
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
  EQMESH_ASSIGN_OR_RETURN(bool bracketed, Bracket(probe, meets, start_code, &lo, &hi));
  if (!bracketed) return hi;
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

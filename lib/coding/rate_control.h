// Rate control: choose the R-D slope lambda that meets a size or quality target.
//
// lambda travels in the header as a log2 code (bitstream_shared.h), so the search
// runs over integer codes: bracket (a size target steps where a model of the
// stream's growth puts it; a quality target by doubling steps), then narrow the
// bracket by interpolation kept in check by bisection (rate_control.cpp). Both the rate
// and the quality grow (almost) monotonically with lambda; where they do not, the
// search still terminates and returns the best point it saw.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/status.h"

namespace eqmesh {

struct RatePoint {
  int64_t lambda_code = 0;
  std::vector<uint8_t> bytes;
  double bpv = 0;
  double psnr_db = 0;  // only when the evaluator measures quality
};

using RateEvaluator = std::function<StatusOr<RatePoint>(int64_t lambda_code)>;

struct RateSearchReport {
  int evaluations = 0;
};

// The first point found whose bpv is within rel_tolerance of target_bpv (the
// closest one seen otherwise).
StatusOr<RatePoint> SearchForRate(const RateEvaluator& eval, double target_bpv, int64_t start_code,
                                  double rel_tolerance = 0.03, RateSearchReport* report = nullptr);

// The smallest stream whose psnr_db >= target_psnr; the largest-lambda point if
// none reaches it (the caller reports the shortfall).
StatusOr<RatePoint> SearchForQuality(const RateEvaluator& eval, double target_psnr,
                                     int64_t start_code, RateSearchReport* report = nullptr);

// Byte-budget search for embedded streams (coder 1, zerotree): a budget of B bytes
// yields a stream of size <= B whose quality grows with B until the stream is
// complete (size < B).
struct BudgetPoint {
  uint64_t budget = 0;
  uint64_t size = 0;   // bytes of the stream the budget gave
  double psnr_db = 0;
};
using BudgetEvaluator = std::function<StatusOr<BudgetPoint>(uint64_t budget)>;

// The smallest budget (within 1 %) whose psnr_db >= target_psnr, searched by
// doubling / halving from start and bisecting log(budget); the best point seen
// when no budget reaches it (the complete stream or the evaluation cap).
StatusOr<BudgetPoint> SearchBudgetForQuality(const BudgetEvaluator& eval, double target_psnr, uint64_t start,
                                             uint64_t min_budget, RateSearchReport* report = nullptr);

}  // namespace eqmesh

// Rate control: choose the R-D slope lambda that meets a size or quality target.
//
// lambda travels in the header as a log2 code (bitstream_shared.h), so the search
// runs over integer codes: bracket by doubling steps, then bisect. Both the rate
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

// The point whose bpv is within rel_tolerance of target_bpv (closest otherwise).
StatusOr<RatePoint> SearchForRate(const RateEvaluator& eval, double target_bpv, int64_t start_code,
                                  double rel_tolerance = 0.03, RateSearchReport* report = nullptr);

// The smallest stream whose psnr_db >= target_psnr; the largest-lambda point if
// none reaches it (the caller reports the shortfall).
StatusOr<RatePoint> SearchForQuality(const RateEvaluator& eval, double target_psnr,
                                     int64_t start_code, RateSearchReport* report = nullptr);

}  // namespace eqmesh

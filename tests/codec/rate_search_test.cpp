// The lambda-code searches of rate_control.h on synthetic quality curves: the
// answer they must give is known exactly, whatever the path.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "coding/rate_control.h"

namespace eqmesh {
namespace {

using Curve = std::function<double(int64_t)>;

// Points on the given quality and size curves (by default, the size doubling
// every 16 codes), counting the calls.
RateEvaluator Evaluating(const Curve& psnr, int* calls,
                         const Curve& bpv = [](int64_t c) { return std::exp2(static_cast<double>(c) / 16.0); }) {
  return [psnr, bpv, calls](int64_t code) -> StatusOr<RatePoint> {
    ++*calls;
    RatePoint p;
    p.lambda_code = code;
    p.psnr_db = psnr(code);
    p.bpv = bpv(code);
    return p;
  };
}

// The smallest code in [-range, range] whose quality meets the target, by brute force.
int64_t SmallestMeeting(const Curve& psnr, double target, int64_t range = 400) {
  for (int64_t c = -range; c <= range; ++c) {
    if (psnr(c) >= target) return c;
  }
  return range + 1;
}

TEST(RateSearch, QualitySearchFindsTheSmallestCodeThatMeetsAMonotoneTarget) {
  const Curve curves[] = {
      [](int64_t c) { return 60.0 + 0.1 * static_cast<double>(c); },                  // linear
      [](int64_t c) { return 70.0 + 10.0 * std::tanh(static_cast<double>(c) / 20.0); },  // saturating
      [](int64_t c) { return 50.0 + 0.5 * std::floor(static_cast<double>(c) / 7.0); },   // steps
  };
  for (const Curve& psnr : curves) {
    for (double target : {55.5, 63.37, 71.2, 75.01}) {
      for (int64_t start : {-90, 0, 17, 120}) {
        const int64_t want = SmallestMeeting(psnr, target);
        if (want > 400 || want == -400) continue;  // the answer lies beyond the brute-force range
        int calls = 0;
        auto got = SearchForQuality(Evaluating(psnr, &calls), target, start);
        ASSERT_TRUE(got.ok()) << got.status().message();
        EXPECT_EQ(got->lambda_code, want) << "target " << target << " start " << start;
        EXPECT_GE(got->psnr_db, target);
      }
    }
  }
}

TEST(RateSearch, QualitySearchNarrowsALinearBracketInAFewEvaluations) {
  // The interpolated guess lands next to the answer; its neighbour closes the
  // interval. Bisection alone would take four evaluations after the bracket.
  const Curve linear = [](int64_t c) { return 60.0 + 0.1 * static_cast<double>(c); };
  int calls = 0;
  auto got = SearchForQuality(Evaluating(linear, &calls), 61.23, 0);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->lambda_code, 13);
  EXPECT_LE(calls, 4) << "bracket (0, 16), then the guess 13 and its neighbour 12";
}

TEST(RateSearch, QualitySearchOutOfReachReturnsTheBestPointItSaw) {
  const Curve capped = [](int64_t c) { return 40.0 + 10.0 * std::tanh(static_cast<double>(c) / 50.0); };
  int calls = 0;
  auto got = SearchForQuality(Evaluating(capped, &calls), 60.0, 0);
  ASSERT_TRUE(got.ok());
  EXPECT_LT(got->psnr_db, 60.0);
  EXPECT_GT(got->psnr_db, 49.0) << "the highest code searched, near the cap";
}

TEST(RateSearch, InfiniteQualityIsBisectedNotInterpolated) {
  // A lossless stream measures +inf; interpolating toward it must not leave the bracket.
  const Curve lossless_above = [](int64_t c) { return c >= 9 ? INFINITY : 60.0 + 0.1 * static_cast<double>(c); };
  int calls = 0;
  auto got = SearchForQuality(Evaluating(lossless_above, &calls), 61.5, 0);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->lambda_code, 9);
}

RateEvaluator SizeEvaluating(const Curve& bpv, int* calls) {
  return Evaluating([](int64_t) { return 0.0; }, calls, bpv);
}

// bpv doubling every `codes` codes, 1 bpv at code 0.
Curve SizeDoublingEvery(double codes) {
  return [codes](int64_t c) { return std::exp2(static_cast<double>(c) / codes); };
}

TEST(RateSearch, RateSearchOnTheModelsSlopeNeedsTwoEvaluations) {
  // The first point and the one the size model steps to, from up to eight
  // octaves of lambda away.
  for (const double target : {0.25, 0.6, 1.0, 2.5, 8.0}) {
    const auto answer = static_cast<int64_t>(std::lround(36.0 * std::log2(target)));
    for (const int64_t start : {answer - 120, answer - 30, answer + 5, answer + 60, answer + 128}) {
      int calls = 0;
      auto got = SearchForRate(SizeEvaluating(SizeDoublingEvery(36.0), &calls), target, start, 0.03);
      ASSERT_TRUE(got.ok());
      EXPECT_LE(std::abs(got->bpv - target), 0.03 * target) << "target " << target << " from " << start;
      EXPECT_LE(calls, 2) << "target " << target << " from " << start;
    }
  }
}

TEST(RateSearch, RateSearchFindsTheTargetOnOtherSlopes) {
  // Steeper and flatter than the model: the secant through the first two points
  // corrects the slope, and interpolation closes the bracket.
  for (const double codes : {12.0, 20.0, 70.0, 120.0}) {
    for (const double target : {0.3, 1.7, 5.0}) {
      int calls = 0;
      auto got = SearchForRate(SizeEvaluating(SizeDoublingEvery(codes), &calls), target, -40, 0.03);
      ASSERT_TRUE(got.ok());
      // A code moves the size by 2^(1/codes): within 3 % needs codes >= 12.
      EXPECT_LE(std::abs(got->bpv - target), 0.03 * target) << codes << " codes per doubling, target " << target;
      EXPECT_LE(calls, 6) << codes << " codes per doubling, target " << target;
    }
  }
}

TEST(RateSearch, RateSearchBeyondASaturatedSizeReturnsTheLargestItSaw) {
  // Every coefficient coded: more lambda adds nothing (a coarse level count at a
  // high rate target). The search ends at the code range or its evaluation cap.
  const Curve saturated = [](int64_t c) { return std::min(std::exp2(static_cast<double>(c) / 36.0), 0.5); };
  int calls = 0;
  auto got = SearchForRate(SizeEvaluating(saturated, &calls), 2.0, -96, 0.03);
  ASSERT_TRUE(got.ok());
  EXPECT_DOUBLE_EQ(got->bpv, 0.5);
  EXPECT_LE(calls, 12);
}

TEST(RateSearch, RateSearchAcrossAJumpReturnsTheNearerSide) {
  // No code lands within tolerance (most coefficients leave the dead zone at
  // once): the nearer of the two sides comes back.
  const Curve jump = [](int64_t c) { return c < 10 ? 0.8 * std::exp2(static_cast<double>(c) / 200.0) : 1.6; };
  int calls = 0;
  auto got = SearchForRate(SizeEvaluating(jump, &calls), 1.0, -60, 0.03);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->lambda_code, 9);
  EXPECT_LE(calls, 40);
}

}  // namespace
}  // namespace eqmesh

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>

#include "coding/entropy/dead_zone_quantizer.h"
#include "coding/entropy/ggd.h"
#include "coding/entropy/quantizer_table.h"

namespace eqmesh {
namespace {

using Layout = QuantizerTableLayout;

// Adaptive Simpson quadrature, written for the test as an independent check of the
// incomplete-gamma based moments.
double Simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm,
               double fb, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm);
  const double right = (b - m) / 6 * (fm + 4 * frm + fb);
  if (depth <= 0 || std::fabs(left + right - whole) <= 15 * tol) {
    return left + right + (left + right - whole) / 15;
  }
  return Simpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
         Simpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

double Integrate(const std::function<double(double)>& f, double a, double b, double rel_tol) {
  const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  const double whole = (b - a) / 6 * (fa + 4 * fm + fb);
  const double tol = std::max(std::fabs(whole) * rel_tol, 1e-300);
  return Simpson(f, a, b, fa, fm, fb, whole, tol, 40);
}

TEST(Ggd, IncompleteGammaKnownValues) {
  // P(1, x) = 1 - e^-x; P(1/2, x) = erf(sqrt x).
  for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(RegularizedGamma(1.0, x).p, 1 - std::exp(-x), 1e-14);
    EXPECT_NEAR(RegularizedGamma(1.0, x).q / std::exp(-x), 1.0, 1e-12);
    EXPECT_NEAR(RegularizedGamma(0.5, x).p, std::erf(std::sqrt(x)), 1e-14);
    EXPECT_NEAR(RegularizedGamma(0.5, x).q / std::erfc(std::sqrt(x)), 1.0, 1e-11);
  }
}

TEST(Ggd, UnitVarianceAndMomentsMatchQuadrature) {
  for (int s = 0; s < Layout::kShapeCount; s += 3) {
    const UnitGgd g(Layout::Shape(s));
    auto f = [&](double x) { return g.Density(x); };
    auto xf = [&](double x) { return x * g.Density(x); };
    const UnitGgd::Moments all = g.OnInterval(0, INFINITY);
    EXPECT_NEAR(all.mass, 0.5, 1e-13);
    EXPECT_NEAR(all.second, 0.5, 1e-13);
    for (auto [lo, hi] : {std::pair{0.0, 0.3}, {0.3, 0.9}, {1.0, 2.5}, {4.0, 4.5}}) {
      const UnitGgd::Moments m = g.OnInterval(lo, hi);
      EXPECT_NEAR(m.mass / Integrate(f, lo, hi, 1e-13), 1.0, 1e-9) << s << " " << lo;
      EXPECT_NEAR(m.first / Integrate(xf, lo, hi, 1e-13), 1.0, 1e-9) << s << " " << lo;
    }
  }
}

// Committed table against direct quadrature of the density: bin frequencies within
// the rounding of 2^15 (the largest bin absorbs the remainder) and centroids within
// two Q16 units.
TEST(QuantizerTable, BinsAndCentroidsMatchQuadrature) {
  for (int s : {0, 3, 5, 10, 15}) {
    const UnitGgd g(Layout::Shape(s));
    auto f = [&](double x) { return g.Density(x); };
    auto xf = [&](double x) { return x * g.Density(x); };
    for (int b : {4, 20, 36, 52, 68, 80}) {
      const QuantizerEntry& e = GetQuantizer(s, b);
      if (e.codes_nothing()) continue;
      const double step = e.step_q16 / 65536.0, z = e.dead_zone_q16 / 65536.0;
      int largest = 0;
      uint32_t sum = 0;
      for (int k = 0; k <= e.max_index; ++k) {
        sum += e.freq[k];
        if (e.freq[k] > e.freq[largest]) largest = k;
      }
      EXPECT_EQ(sum, 1u << kQuantizerFreqBits);
      for (int k = 0; k <= e.max_index; ++k) {
        EXPECT_GE(e.freq[k], 1);
        double p;
        if (k == 0) {
          p = 2 * Integrate(f, 0, z, 1e-12);
        } else if (k < e.max_index) {
          p = 2 * Integrate(f, z + (k - 1) * step, z + k * step, 1e-12);
        } else {
          const double lo = z + (k - 1) * step;
          p = 2 * Integrate(f, lo, lo + 200.0, 1e-12);
        }
        if (k != largest) {
          EXPECT_LE(std::fabs(e.freq[k] - p * 32768.0), 0.5 + 1e-6 + (p * 32768 < 1 ? 1 : 0))
              << "shape " << s << " bucket " << b << " bin " << k;
        }
      }
      for (int k = 1; k <= e.max_index; ++k) {
        const double lo = z + (k - 1) * step, hi = lo + step;
        const double mass = Integrate(f, lo, hi, 1e-13);
        if (mass < 1e-200) continue;
        const double centroid = Integrate(xf, lo, hi, 1e-13) / mass;
        EXPECT_NEAR(e.recon_offset[k - 1], (centroid - lo) * 65536.0, 2.0)
            << "shape " << s << " bucket " << b << " bin " << k;
      }
    }
  }
}

// Larger lambda sigma^2 must give a higher rate and a lower distortion (the table is
// an argmin over one fixed grid for every bucket) and, above one bit, a finer
// or equal step.
TEST(QuantizerTable, RateDistortionMonotoneInLambda) {
  for (int s = 0; s < Layout::kShapeCount; s += 3) {
    const UnitGgd g(Layout::Shape(s));
    double prev_rate = -1, prev_dist = 2, prev_step = 1e9;
    for (int b = 0; b < Layout::kBucketCount; ++b) {
      const QuantizerEntry& e = GetQuantizer(s, b);
      double rate = 0, dist = 1, step = 1e9;
      if (!e.codes_nothing()) {
        const DeadZoneModel m = EvaluateDeadZone(g, e.step_q16 / 65536.0, e.dead_zone_q16 / 65536.0);
        rate = m.rate;
        dist = m.distortion;
        step = e.step_q16 / 65536.0;
      }
      EXPECT_GE(rate, prev_rate - 1e-12) << s << " " << b;
      EXPECT_LE(dist, prev_dist + 1e-12) << s << " " << b;
      // At very low rates the dead zone, not the step, carries the trade-off (the
      // steps there are wider than the data); the step is monotone above that.
      if (rate > 1.0) {
        EXPECT_LE(step, prev_step) << s << " " << b << " rate " << rate;
      }
      prev_rate = rate;
      prev_dist = dist;
      prev_step = step;
    }
    // At the fine end the high-rate law D ~ step^2 / 12 holds closely.
    const QuantizerEntry& fine = GetQuantizer(s, Layout::kBucketCount - 1);
    const double step = fine.step_q16 / 65536.0;
    EXPECT_NEAR(EvaluateDeadZone(g, step, fine.dead_zone_q16 / 65536.0).distortion / (step * step / 12),
                1.0, 0.1);
  }
}

// The committed file is normative; regenerating some shapes here must reproduce it
// exactly (the full file: run eqmesh_generate_quantizer_tables and diff).
TEST(QuantizerTable, RegenerationMatchesCommittedTables) {
  for (int s : {0, 7, 15}) {
    const std::vector<DesignedQuantizer> designed = DesignShapeTable(s);
    ASSERT_EQ(designed.size(), static_cast<size_t>(Layout::kBucketCount));
    for (int b = 0; b < Layout::kBucketCount; ++b) {
      const DesignedQuantizer& d = designed[b];
      const QuantizerEntry& e = GetQuantizer(s, b);
      ASSERT_EQ(e.step_q16, d.step_q16) << s << " " << b;
      if (d.step_q16 == 0) continue;
      ASSERT_EQ(e.dead_zone_q16, d.dead_zone_q16);
      ASSERT_EQ(static_cast<size_t>(e.max_index), d.recon_offset.size());
      for (int k = 0; k <= e.max_index; ++k) EXPECT_EQ(e.freq[k], d.freq[k]);
      for (int k = 0; k < e.max_index; ++k) EXPECT_EQ(e.recon_offset[k], d.recon_offset[k]);
    }
  }
}

// FNV-1a 64 of every entry as GetQuantizer returns it (step, dead zone, M, the M + 1
// frequencies, the M reconstruction offsets; a code-nothing entry as 0, 0, 0; each value
// as 8 little-endian bytes), pinned from the plain arrays committed before the tables
// were packed: unpacking must give back exactly those numbers.
TEST(QuantizerTable, UnpackedTablesMatchChecksumOfPlainTables) {
  uint64_t hash = 14695981039346656037ull;
  auto mix = [&hash](int64_t v) {
    for (int i = 0; i < 8; ++i) {
      hash ^= (static_cast<uint64_t>(v) >> (8 * i)) & 0xff;
      hash *= 1099511628211ull;
    }
  };
  int coded = 0;
  int64_t freq_count = 0, recon_count = 0;
  for (int s = 0; s < kQuantizerShapeCount; ++s) {
    for (int b = 0; b < kQuantizerBucketCount; ++b) {
      const QuantizerEntry& e = GetQuantizer(s, b);
      mix(e.step_q16);
      mix(e.dead_zone_q16);
      mix(e.max_index);
      if (e.codes_nothing()) continue;
      ++coded;
      for (int k = 0; k <= e.max_index; ++k) mix(e.freq[k]);
      for (int k = 0; k < e.max_index; ++k) mix(e.recon_offset[k]);
      freq_count += e.max_index + 1;
      recon_count += e.max_index;
    }
  }
  EXPECT_EQ(coded, 1721);
  EXPECT_EQ(freq_count, 76704);
  EXPECT_EQ(recon_count, 74983);
  EXPECT_EQ(hash, 0xf285ba1e20da27f1ull);

  const QuantizerEntry& first = GetQuantizer(0, 0);
  EXPECT_EQ(first.step_q16, 524288);
  EXPECT_EQ(first.dead_zone_q16, 1015808);
  ASSERT_EQ(first.max_index, 3);
  EXPECT_EQ(first.freq[0], 32765);
  EXPECT_EQ(first.freq[3], 1);
  EXPECT_EQ(first.recon_offset[0], 145169);
  EXPECT_EQ(first.recon_offset[2], 171484);
  const QuantizerEntry& mid = GetQuantizer(3, 60);
  EXPECT_EQ(mid.step_q16, 4096);
  EXPECT_EQ(mid.dead_zone_q16, 2048);
  ASSERT_EQ(mid.max_index, 64);
  EXPECT_EQ(mid.freq[1], 3264);
  EXPECT_EQ(mid.freq[64], 198);
  EXPECT_EQ(mid.recon_offset[63], 2024);
  const QuantizerEntry& last = GetQuantizer(15, kQuantizerBucketCount - 1);
  EXPECT_EQ(last.step_q16, 45);
  EXPECT_EQ(last.dead_zone_q16, 22);
  ASSERT_EQ(last.max_index, 64);
  EXPECT_EQ(last.freq[0], 9);
  EXPECT_EQ(last.freq[64], 31625);
  EXPECT_EQ(last.recon_offset[0], 22);
  EXPECT_TRUE(GetQuantizer(7, 0).codes_nothing());
}

TEST(QuantizerTable, BucketLookupIsIntegerAndClamped) {
  EXPECT_EQ(QuantizerBucket(-16 * 4 - 1), -1);                 // just below 2^-4
  EXPECT_EQ(QuantizerBucket(-16 * 4), 0);                      // lambda' = 2^-4
  EXPECT_EQ(QuantizerBucket(-16 * 4 + 3), 0);
  EXPECT_EQ(QuantizerBucket(-16 * 4 + 4), 1);                  // next quarter octave
  EXPECT_EQ(QuantizerBucket(int64_t{1} << 50), kQuantizerBucketCount - 1);
  EXPECT_EQ(QuantizerBucket(-(int64_t{1} << 50)), -1);
  EXPECT_TRUE(GetQuantizer(3, -1).codes_nothing());
  const QuantizerEntry& e = GetQuantizer(10, 40);
  ASSERT_FALSE(e.codes_nothing());
  // Reconstructions increase with the index and stay inside their bins.
  for (int k = 1; k < e.max_index + 5; ++k) {
    const int64_t r = e.ReconstructionQ16(k);
    EXPECT_GT(r, e.dead_zone_q16 + int64_t{k - 1} * e.step_q16);
    EXPECT_LT(r, e.dead_zone_q16 + int64_t{k} * e.step_q16);
  }
}

}  // namespace
}  // namespace eqmesh

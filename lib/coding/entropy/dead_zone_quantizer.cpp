// Dead-zone quantizer model and R-D design: see dead_zone_quantizer.h for the papers
// followed and the departures.
#include "coding/entropy/dead_zone_quantizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace eqmesh {
namespace {

using Layout = QuantizerTableLayout;

// Entropy contribution (bits) of one signed bin pair holding two-sided mass p.
double PairEntropy(double p) { return p > 0 ? -p * std::log2(p / 2.0) : 0.0; }

// Variance contribution of a bin around its own centroid; cancellation can leave a
// tiny negative number in very narrow bins.
double BinDistortion(const UnitGgd::Moments& m) {
  if (m.mass <= 0) return 0;
  return std::max(0.0, m.second - m.first * m.first / m.mass);
}

// Frequencies of the masses, every one >= 1, summing to exactly 2^kFreqBits; the
// largest absorbs the rounding so small bins keep their relative accuracy.
std::vector<uint16_t> QuantizeFrequencies(const std::vector<double>& mass) {
  const int64_t total = int64_t{1} << Layout::kFreqBits;
  std::vector<int64_t> f(mass.size());
  int64_t sum = 0;
  size_t largest = 0;
  for (size_t k = 0; k < mass.size(); ++k) {
    f[k] = std::max<int64_t>(1, std::llround(mass[k] * static_cast<double>(total)));
    sum += f[k];
    if (f[k] > f[largest]) largest = k;
  }
  f[largest] += total - sum;
  std::vector<uint16_t> out(f.size());
  for (size_t k = 0; k < f.size(); ++k) out[k] = static_cast<uint16_t>(f[k]);
  return out;
}

struct GridPoint {
  double rate, distortion;
  int32_t step_q16, dead_zone_q16;
};

// The finite search grid: step 2^(i/8) for i in [-96, 24], z = step (8 + k) / 16 for
// k in [0, 40] (k in [0, 16] below step 1/8, where wide dead zones never win), plus
// "code nothing" first.
std::vector<GridPoint> EvaluateGrid(const UnitGgd& ggd) {
  std::vector<GridPoint> grid;
  grid.push_back({0.0, 1.0, 0, 0});
  for (int i = -96; i <= 24; ++i) {
    const int64_t step = std::llround(65536.0 * std::exp2(i / 8.0));
    for (int k = 0; k <= (i < -24 ? 16 : 40); ++k) {
      const int64_t dz = step * (8 + k) / 16;
      const DeadZoneModel m = EvaluateDeadZone(ggd, static_cast<double>(step) / 65536.0,
                                                static_cast<double>(dz) / 65536.0);
      grid.push_back({m.rate, m.distortion, static_cast<int32_t>(step), static_cast<int32_t>(dz)});
    }
  }
  return grid;
}

}  // namespace

DeadZoneModel EvaluateDeadZone(const UnitGgd& ggd, double step, double dead_zone,
                               double tail_epsilon, int max_bins) {
  DeadZoneModel out;
  UnitGgd::EdgeGammas lo = ggd.AtEdge(0.0);
  UnitGgd::EdgeGammas hi = ggd.AtEdge(dead_zone);
  const UnitGgd::Moments zero = ggd.Between(lo, hi);
  out.mass.push_back(2 * zero.mass);
  out.centroid.push_back(0.0);
  out.rate = out.mass[0] > 0 ? -out.mass[0] * std::log2(out.mass[0]) : 0.0;
  out.distortion = 2 * zero.second;
  for (int k = 1; k <= max_bins && hi.g[0].q >= tail_epsilon; ++k) {
    lo = hi;
    hi = ggd.AtEdge(dead_zone + k * step);
    const UnitGgd::Moments m = ggd.Between(lo, hi);
    out.mass.push_back(2 * m.mass);
    out.centroid.push_back(m.mass > 0 ? m.first / m.mass : dead_zone + (k - 0.5) * step);
    out.rate += PairEntropy(2 * m.mass);
    out.distortion += 2 * BinDistortion(m);
  }
  const double edge = dead_zone + static_cast<double>(out.mass.size() - 1) * step;
  const UnitGgd::Moments tail = ggd.Between(hi, ggd.AtEdge(std::numeric_limits<double>::infinity()));
  out.tail_mass = 2 * tail.mass;
  if (hi.g[0].q < tail_epsilon) {
    // Negligible: lumped into one open bin per side.
    out.rate += PairEntropy(out.tail_mass);
    out.distortion += 2 * BinDistortion(tail);
  } else {
    // High-rate pricing of the rest: -log2 f(x) = -log2 f(0) + (eta|x|)^nu / ln 2.
    out.rate += out.tail_mass * (-(ggd.LogDensityAtZero() + std::log(step)) / std::log(2.0)) +
                ggd.TwoSidedTailPowerMoment(edge) / std::log(2.0);
    out.distortion += out.tail_mass * step * step / 12.0;
  }
  return out;
}

DesignedQuantizer IntegerizeQuantizer(const UnitGgd& ggd, int32_t step_q16, int32_t dead_zone_q16) {
  DesignedQuantizer q;
  q.step_q16 = step_q16;
  q.dead_zone_q16 = dead_zone_q16;
  if (step_q16 == 0) return q;
  const double step = step_q16 / 65536.0, z = dead_zone_q16 / 65536.0;
  // M: the open bin [z + (M-1) step, inf) holds less than kOpenBinMass, or the cap.
  int max_index = 1;
  while (max_index < Layout::kMaxIndexCap &&
         ggd.TwoSidedTail(z + (max_index - 1) * step) >= Layout::kOpenBinMass) {
    ++max_index;
  }
  std::vector<double> mass;
  mass.push_back(2 * ggd.OnInterval(0.0, z).mass);
  for (int k = 1; k <= max_index; ++k) {
    const double lower = z + (k - 1) * step;
    const UnitGgd::Moments m = ggd.OnInterval(lower, lower + step);
    if (k < max_index) mass.push_back(2 * m.mass);
    const double offset = m.mass > 0 ? m.first / m.mass - lower : step / 2;
    q.recon_offset.push_back(static_cast<int32_t>(std::llround(offset * 65536.0)));
  }
  mass.push_back(ggd.TwoSidedTail(z + (max_index - 1) * step));
  q.freq = QuantizeFrequencies(mass);
  return q;
}

std::vector<DesignedQuantizer> DesignShapeTable(int shape_index) {
  const UnitGgd ggd(Layout::Shape(shape_index));
  const std::vector<GridPoint> grid = EvaluateGrid(ggd);
  std::map<size_t, DesignedQuantizer> integerized;
  std::vector<DesignedQuantizer> table;
  for (int b = 0; b < Layout::kBucketCount; ++b) {
    const double lambda = std::exp2(Layout::Log2Lambda(b));
    size_t best = 0;
    for (size_t g = 1; g < grid.size(); ++g) {
      const double j = grid[g].rate + lambda * grid[g].distortion;
      if (j < grid[best].rate + lambda * grid[best].distortion) best = g;
    }
    auto it = integerized.find(best);
    if (it == integerized.end()) {
      DesignedQuantizer q = IntegerizeQuantizer(ggd, grid[best].step_q16, grid[best].dead_zone_q16);
      q.rate = grid[best].rate;
      q.distortion = grid[best].distortion;
      it = integerized.emplace(best, std::move(q)).first;
    }
    table.push_back(it->second);
  }
  return table;
}

}  // namespace eqmesh

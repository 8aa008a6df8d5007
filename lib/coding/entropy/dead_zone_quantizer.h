// Entropy-constrained dead-zone uniform scalar quantizers for a unit-variance GGD,
// the quantizers of the EQ coder (LoPresto, Ramchandran, Orchard, DCC 1997; Lavu,
// Choi, Baraniuk, SGP 2003, Sec. 3.2): zero bin [-z, z], bins of width step beyond,
// reconstruction at the conditional mean of each bin (Sullivan 1996 shows centroid
// reconstruction with a widened dead zone is near-optimal for Laplacian sources).
// Rate = entropy of the bin probabilities, distortion = MSE; the pair (step, z) is
// chosen per (shape, lambda') by exhaustive search of a fixed grid, minimising
// J = R + lambda' D. By scale invariance the quantizer for (sigma, lambda) is sigma
// times the unit-sigma one for lambda' = lambda sigma^2.
//
// Departures: the search grid is finite (step 2^(i/8) from 2^-12 to 2^3, z/step =
// 1/2 + k/16 up to 3 for coarse steps and up to 3/2 below step 1/8), so the
// optimum is a grid optimum; a "code nothing" quantizer (everything in the zero bin,
// R = 0, D = 1) is part of the grid. Everything here is double precision and runs
// offline: the integer tables it produces (quantizer_tables.inc) are normative.
#pragma once

#include <cstdint>
#include <vector>

#include "coding/entropy/ggd.h"

namespace eqmesh {

// R and D of the dead-zone quantizer (step, dead_zone) on a unit GGD, plus the
// magnitude-bin masses (two-sided) and centroids of the positive bins.
struct DeadZoneModel {
  double rate = 0;        // bits per sample
  double distortion = 0;  // mean squared error, unit variance
  std::vector<double> mass;      // mass[k]: P(|q| = k), k = 0 .. last closed bin
  std::vector<double> centroid;  // centroid[k] of bin k > 0 (centroid[0] = 0)
  double tail_mass = 0;          // mass beyond the last listed bin (both sides)
};
// Bins are summed explicitly until the tail holds less than tail_epsilon or max_bins
// bins were summed; a remaining tail is then priced by the high-rate approximation
// (entropy -int f log2(f step), distortion step^2 / 12 per unit mass), accurate once
// bins are narrow against the density's variation, which is the only case where
// max_bins is reached.
DeadZoneModel EvaluateDeadZone(const UnitGgd& ggd, double step, double dead_zone,
                               double tail_epsilon = 1e-10, int max_bins = 400);

// The integer form of one table entry, as committed in quantizer_tables.inc.
struct DesignedQuantizer {
  int32_t step_q16 = 0;  // 0: code nothing
  int32_t dead_zone_q16 = 0;
  std::vector<uint16_t> freq;         // magnitudes 0..M, M = open (escape) bin; sum 2^15
  std::vector<int32_t> recon_offset;  // k = 1..M: centroid - lower edge of bin k, Q16
  double rate = 0, distortion = 0;    // of the chosen grid point (for tests, not stored)
};

// Table layout shared by the generator, the runtime table and tests.
struct QuantizerTableLayout {
  static constexpr int kShapeCount = 16;            // nu = 0.5, 0.6, ..., 2.0
  static constexpr int kBucketCount = 113;          // log2 lambda' in quarter octaves
  static constexpr int kBucketMinQuarter = -16;     // bucket 0 starts at lambda' = 2^-4
  static constexpr int kMaxIndexCap = 64;           // at most 65 magnitude symbols
  static constexpr int kFreqBits = 15;
  static constexpr double kOpenBinMass = 1e-6;      // M: open bin below this mass
  static double Shape(int shape_index) { return (5 + shape_index) / 10.0; }
  // Design point of a bucket: the middle of its quarter octave.
  static double Log2Lambda(int bucket) { return (kBucketMinQuarter + bucket + 0.5) / 4.0; }
};

// R-D optimal entries of every bucket for one shape (grid search shared by buckets).
std::vector<DesignedQuantizer> DesignShapeTable(int shape_index);

// Integer entry for a given grid point (exposed for tests).
DesignedQuantizer IntegerizeQuantizer(const UnitGgd& ggd, int32_t step_q16, int32_t dead_zone_q16);

}  // namespace eqmesh

// How many levels to send: the scale-wise R-D choice the rate targets need.
//
// The stream is scale-wise progressive (Lavu, Choi, Baraniuk 2003 §3; PGC), so a
// stream of K < L levels is an ordinary stream of the mesh truncated to level K.
// The seed codes every level of its normal meshes; ours are refined until the
// remesh error is far below the codec's (up to ~12x the input vertex count), and
// at low rates the finest levels then cost more than they return: every one of
// their coefficients, even quantized to zero, costs some bits. Measured
// (horse.ply, --bpv 1, EQ unlifted, `eqmesh encode --levels K --measure`):
// 3 levels 67.8 dB, 4 levels 66.6, 5 levels 60.5, 6 levels 54.7.
//
// So for a bpv target the encoder codes the mesh truncated to K = 1, 2, ... levels,
// each at the target rate, measures each decoded stream against the original
// (the same Metro meter as `eqmesh compare`), and keeps the best; for a PSNR
// target it keeps the smallest stream that meets it, skipping level counts whose
// uncoded truncated mesh already misses it. Both scans stop once a further level
// makes things worse. Departure from the seed: the level count is
// an encoder decision by measurement, not a property of the input.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "coding/encoder.h"
#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct LevelCountTrial {
  int levels = 0;
  double bpv = 0;
  double psnr_db = 0;
  size_t bytes = 0;
  bool feasible = true;  // PSNR target: met; bpv target: always true
  // False where a PSNR target was above this count's uncoded (truncated) PSNR,
  // which psnr_db then holds: not encoded, bpv and bytes 0.
  bool coded = true;
};

struct LevelCountReport {
  std::vector<LevelCountTrial> trials;
  int chosen_levels = 0;
};

// `mesh` truncated to its first `levels` levels (positions, kinds, hierarchy).
StatusOr<SemiRegularMesh> TruncateLevels(const SemiRegularMesh& mesh, int levels);

// A PSNR target asks the remesher for a remesh this much better
// (RemeshOptions::min_psnr): coding adds error to the remesh's own.
inline constexpr double kRemeshMarginDb = 1.0;

// PSNR of the whole remesh, uncoded, against `original` (at the ranking sample
// count): no stream of it can measure higher.
StatusOr<double> RemeshCeilingPsnr(const SemiRegularMesh& mesh, const Mesh& original);

// What a kTargetOutOfReach error of EncodeChoosingLevels says was reached: the
// text after "is out of reach: " ("the best stream measures 68.12 dB"), or the
// whole message of any other status. Where the whole mesh uncoded missed the
// target it begins with kUncodedCeiling, which callers may rename for what
// their mesh is.
inline constexpr char kUncodedCeiling[] = "the remesh itself";
std::string OutOfReachReached(const Status& status);

// Encode() with the level count chosen as above. Without a bpv or PSNR target, or
// without options.original, this is Encode() on all levels. The report's PSNR is
// always measured when the search ran. A PSNR target that no stream meets is a
// kTargetOutOfReach error naming the best PSNR measured (the uncoded remesh's
// when even that misses it): the caller never gets a stream short of its target.
StatusOr<std::vector<uint8_t>> EncodeChoosingLevels(const SemiRegularMesh& mesh,
                                                    const EncodeOptions& options,
                                                    EncodeReport* report = nullptr,
                                                    LevelCountReport* levels = nullptr);

}  // namespace eqmesh

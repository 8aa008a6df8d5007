// Metro-style symmetric surface distance between two triangle meshes: the
// error measure behind every rate-distortion number eqmesh reports.
//
// Follows Cignoni, Rocchini, Scopigno, "Metro: measuring error on simplified
// surfaces" (CGF 1998) as used by the normal-mesh / PGC papers: sample each
// surface uniformly by area, take each sample's distance to the closest point
// of the other surface, and report RMS, mean and max per direction. Symmetric
// RMS = max(RMS(a->b), RMS(b->a)); PSNR = 20 log10(bbox diagonal of a / RMS).
// Departures are documented in area_sampler.h (area-only, stratified samples).
// The Hausdorff value is the largest *sampled* distance, so it can only
// underestimate the true Hausdorff distance (as in Metro).
#pragma once

#include <cstdint>
#include <memory>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct CompareOptions {
  uint64_t samples = 0;     // per direction; 0 = DefaultSampleCount(a)
  uint64_t seed = 0x5eed;
  int threads = 0;          // 0 = hardware concurrency; results never depend on it
};

struct SurfaceDistance {
  double rms_ab = 0.0, rms_ba = 0.0, rms = 0.0;     // rms = max of the two
  double mean_ab = 0.0, mean_ba = 0.0, mean = 0.0;  // mean = max of the two
  double hausdorff_ab = 0.0, hausdorff_ba = 0.0;
  double hausdorff = 0.0;                           // max over both directions
  double bbox_diagonal = 0.0;                       // of the ORIGINAL (a)
  double psnr_db = 0.0;                             // +inf when rms == 0
  uint64_t samples = 0;                             // per direction
};

// Largest sample count accepted (memory is O(samples / 4096), time is not).
inline constexpr uint64_t kMaxCompareSamples = 1'000'000'000;

// The sample count used when CompareOptions::samples == 0: 10 per vertex of the
// original, clamped to 1M..20M (see the .cpp for the measurement that chose it),
// so the meter's reading of an approximation does not depend on how many
// vertices the approximation has.
uint64_t DefaultSampleCount(const Mesh& original);

// The checks CompareSurfaces makes on each input: at least one vertex and one
// face, indices in range, finite coordinates, non-zero area.
Status ValidateForCompare(const Mesh& mesh);

// a is the original (its bbox diagonal is the PSNR peak), b the approximation.
// Deterministic: the same inputs and options give bit-identical doubles for
// any thread count.
StatusOr<SurfaceDistance> CompareSurfaces(const Mesh& a, const Mesh& b,
                                          const CompareOptions& options = {});

// The approximation side of a comparison kept for the next one: its search
// tree. An encoder measures series of meshes with one connectivity (the trial
// streams of one level count, which differ only in positions); a Compare given
// the series refits the tree of the last mesh when the faces are the same
// (TriangleBvh::Refit) instead of building one, which gives the same doubles
// without a build's time and allocations. One series per thread at a time.
class ApproximationSeries {
 public:
  ApproximationSeries();
  ~ApproximationSeries();
  ApproximationSeries(ApproximationSeries&&) noexcept;
  ApproximationSeries& operator=(ApproximationSeries&&) noexcept;

  struct State;  // opaque: defined where the meter uses it

 private:
  friend class ReferenceSurface;
  std::unique_ptr<State> state_;
};

// The original side of CompareSurfaces prepared once (its scale, area sampler
// and search tree), for measuring many meshes against one original: the
// encoder's searches measure every trial stream, the remesher every retried
// remesh. Compare(b, options) gives the doubles CompareSurfaces(a, b, options)
// gives. Keeps its own copy of `a`; copies share the prepared state.
class ReferenceSurface {
 public:
  // Fails where CompareSurfaces would fail on `a` as the original.
  static StatusOr<ReferenceSurface> Build(const Mesh& a);

  StatusOr<SurfaceDistance> Compare(const Mesh& b, const CompareOptions& options = {},
                                    ApproximationSeries* series = nullptr) const;

 private:
  ReferenceSurface() = default;
  struct Prepared;
  std::shared_ptr<const Prepared> prepared_;
};

// 20 log10(bbox_diagonal / rms); +inf when rms == 0.
double PsnrDb(double bbox_diagonal, double rms);

}  // namespace eqmesh

// AreaSampler: area-uniform random points on a triangle mesh, for the Metro
// meter (Cignoni, Rocchini, Scopigno, "Metro: measuring error on simplified
// surfaces", CGF 1998).
//
// Departure from Metro: Metro samples vertices, edges and faces (Montecarlo,
// subdivision or similar-triangle schemes); we draw area-uniform points only,
// which keeps the RMS an unbiased estimate of the area-weighted RMS. Variance
// is reduced by stratifying along the cumulative-area table: of n samples,
// sample i takes the area quantile (i + u_i) / n, u_i uniform in [0, 1), so
// each triangle gets n * area / total samples up to one, and the count is
// exactly n. Inside the chosen triangle the point is uniform (Turk, "Generating
// random points in triangles", Graphics Gems 1990: sqrt warp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "metrics/sample_rng.h"

namespace eqmesh {

class AreaSampler {
 public:
  // Fails on a mesh without faces, with out-of-range indices, non-finite
  // coordinates or zero total area. Keeps its own copy of the corners.
  static StatusOr<AreaSampler> Build(const Mesh& mesh);

  double total_area() const { return total_area_; }

  // Samples [first, first + count) of an n-sample stratified set, appended to
  // *out. Draws exactly 3 numbers per sample from rng.
  void Sample(uint64_t n, uint64_t first, uint64_t count, SampleRng* rng,
              std::vector<Vec3>* out) const;

  // The same samples (same draws) with the face each lies on and its
  // barycentric coordinates there, for attributes measured at the samples.
  struct Where {
    uint32_t face = 0;
    std::array<double, 3> barycentric{};
  };
  void Sample(uint64_t n, uint64_t first, uint64_t count, SampleRng* rng, std::vector<Vec3>* out,
              std::vector<Where>* where) const;

 private:
  struct Corners {
    Vec3 a, b, c;
  };
  size_t FaceAtArea(double area) const;

  std::vector<Corners> faces_;
  std::vector<double> cumulative_;  // cumulative_[f] = area of faces 0..f
  double total_area_ = 0.0;
  size_t last_positive_ = 0;        // last face with non-zero area
};

}  // namespace eqmesh

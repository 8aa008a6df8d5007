#include "metrics/color_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mesh/triangle_bvh.h"
#include "metrics/area_sampler.h"
#include "core/parallel_blocks.h"

namespace eqmesh {
namespace {

constexpr uint64_t kBlockSize = 4096;  // surface_distance.cpp's blocks: the same samples

struct Direction {
  const AreaSampler& from;
  const SurfaceColor& from_color;
  const TriangleBvh& to_bvh;
  const SurfaceColor& to_color;
  uint64_t samples, seed, direction;
};

double BlockSquaredError(const Direction& d, uint64_t block) {
  const uint64_t first = block * kBlockSize;
  const uint64_t count = std::min(kBlockSize, d.samples - first);
  SampleRng rng = SampleRng::ForBlock(d.seed, d.direction, block);
  std::vector<Vec3> points;
  std::vector<AreaSampler::Where> where;
  d.from.Sample(d.samples, first, count, &rng, &points, &where);
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const ClosestPointResult hit = d.to_bvh.ClosestPoint(points[i]);
    if (!hit.found()) continue;
    const std::array<double, 3> c0 = d.from_color(where[i].face, where[i].barycentric);
    const std::array<double, 3> c1 = d.to_color(hit.face, hit.barycentric);
    for (size_t k = 0; k < 3; ++k) sum += (c0[k] - c1[k]) * (c0[k] - c1[k]);
  }
  return sum;
}

double DirectionRms(const Direction& d, int threads) {
  const uint64_t blocks = (d.samples + kBlockSize - 1) / kBlockSize;
  std::vector<double> sums(blocks, 0.0);
  ForEachBlock(blocks, threads, [&](uint64_t b) { sums[b] = BlockSquaredError(d, b); });
  double total = 0.0;
  for (double s : sums) total += s;  // block order: independent of the thread count
  return std::sqrt(total / (3.0 * static_cast<double>(d.samples)));
}

}  // namespace

StatusOr<ColorDistance> CompareColors(const Mesh& a, const SurfaceColor& color_a, const Mesh& b,
                                      const SurfaceColor& color_b, const CompareOptions& options) {
  auto sampler_a = AreaSampler::Build(a);
  if (!sampler_a.ok()) return sampler_a.status().WithContext("original mesh");
  auto sampler_b = AreaSampler::Build(b);
  if (!sampler_b.ok()) return sampler_b.status().WithContext("other mesh");
  EQMESH_ASSIGN_OR_RETURN(const TriangleBvh bvh_a, TriangleBvh::Build(a));
  EQMESH_ASSIGN_OR_RETURN(const TriangleBvh bvh_b, TriangleBvh::Build(b));
  ColorDistance r;
  r.samples = options.samples > 0 ? options.samples : DefaultSampleCount(a);
  r.rms_ab = DirectionRms({*sampler_a, color_a, bvh_b, color_b, r.samples, options.seed, 0}, options.threads);
  r.rms_ba = DirectionRms({*sampler_b, color_b, bvh_a, color_a, r.samples, options.seed, 1}, options.threads);
  r.rms = std::max(r.rms_ab, r.rms_ba);
  r.psnr_db = r.rms == 0.0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(255.0 / r.rms);
  return r;
}

}  // namespace eqmesh

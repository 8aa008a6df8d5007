// AreaSampler: see area_sampler.h for the papers and the stratification.
#include "metrics/area_sampler.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>  // cross products

namespace eqmesh {

StatusOr<AreaSampler> AreaSampler::Build(const Mesh& mesh) {
  if (mesh.positions.empty()) return InvalidMesh("mesh has no vertices");
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces");
  EQMESH_RETURN_IF_ERROR(CheckIndicesAndCoordinates(mesh));
  AreaSampler sampler;
  sampler.faces_.reserve(mesh.faces.size());
  sampler.cumulative_.reserve(mesh.faces.size());
  double total = 0.0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Corners c{mesh.positions[mesh.faces[f][0]], mesh.positions[mesh.faces[f][1]],
                    mesh.positions[mesh.faces[f][2]]};
    const double area = 0.5 * (c.b - c.a).cross(c.c - c.a).norm();
    if (!std::isfinite(area)) return InvalidMesh("face " + std::to_string(f) + " has a non-finite area");
    if (area > 0.0) sampler.last_positive_ = f;
    total += area;
    sampler.faces_.push_back(c);
    sampler.cumulative_.push_back(total);
  }
  if (!(total > 0.0)) return InvalidMesh("surface has zero area (every face is degenerate)");
  if (!std::isfinite(total)) return InvalidMesh("surface area overflows a double");
  sampler.total_area_ = total;
  return sampler;
}

size_t AreaSampler::FaceAtArea(double area) const {
  // First face whose cumulative area exceeds `area`: zero-area faces, whose
  // cumulative value equals their predecessor's, are never chosen.
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), area);
  if (it == cumulative_.end()) return last_positive_;  // area rounded up to the total
  return static_cast<size_t>(it - cumulative_.begin());
}

void AreaSampler::Sample(uint64_t n, uint64_t first, uint64_t count, SampleRng* rng,
                         std::vector<Vec3>* out) const {
  Sample(n, first, count, rng, out, nullptr);
}

void AreaSampler::Sample(uint64_t n, uint64_t first, uint64_t count, SampleRng* rng, std::vector<Vec3>* out,
                         std::vector<Where>* where) const {
  const double inv_n = 1.0 / static_cast<double>(n);
  for (uint64_t i = first; i < first + count; ++i) {
    const double quantile = (static_cast<double>(i) + rng->NextDouble()) * inv_n;
    const size_t face = FaceAtArea(quantile * total_area_);
    const Corners& c = faces_[face];
    const double s = std::sqrt(rng->NextDouble());
    const double r = rng->NextDouble();
    out->push_back((1.0 - s) * c.a + (s * (1.0 - r)) * c.b + (s * r) * c.c);
    if (where != nullptr) where->push_back({static_cast<uint32_t>(face), {1.0 - s, s * (1.0 - r), s * r}});
  }
}

}  // namespace eqmesh

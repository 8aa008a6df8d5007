// The project's meter (metrics/surface_distance.h) as the encoder's rate control
// and level search use it: PSNR of a mesh, or of a stream once decoded, against
// the original.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

class ReferenceSurface;

// An original prepared once for the meter (metrics' ReferenceSurface): an encode
// measures every trial stream against one original (a horse --psnr 70 encode
// 26 times), and its search tree and area table do not change in between.
struct PreparedOriginal {
  const Mesh* mesh = nullptr;  // what it was prepared from
  std::shared_ptr<const ReferenceSurface> reference;
  // The search tree of the mesh measured last, refitted for the next one when
  // it has the same faces (metrics' ApproximationSeries): a search's trial
  // streams of one level count decode to one connectivity. Taken by one
  // measurement at a time; another measuring meanwhile builds its own tree.
  struct Series;
  std::shared_ptr<Series> series;
};

// kUnsupportedFeature in a build without eqmesh_metrics, as every function here.
StatusOr<std::shared_ptr<const PreparedOriginal>> PrepareOriginal(const Mesh& original);

// `samples` per direction; 0: the meter's default. `prepared`, when it was
// prepared from `original`, saves preparing it again (the same doubles).
StatusOr<double> MeasureMeshPsnr(const Mesh& mesh, const Mesh& original, uint64_t samples = 0,
                                 const PreparedOriginal* prepared = nullptr);
// The stream decoded as the meter measures it: within `max_triangles` (0: every
// triangle of every level).
StatusOr<Mesh> DecodeForMeasure(const std::vector<uint8_t>& stream, uint64_t max_triangles);
// MeasureMeshPsnr of DecodeForMeasure(stream, max_triangles).
StatusOr<double> MeasureStreamPsnr(const std::vector<uint8_t>& stream, const Mesh& original, uint64_t samples = 0,
                                   uint64_t max_triangles = 0, const PreparedOriginal* prepared = nullptr);

}  // namespace eqmesh

// The project's meter (metrics/surface_distance.h) as the encoder's rate control
// and level search use it: PSNR of a mesh, or of a stream once decoded, against
// the original.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// `samples` per direction; 0: the meter's default. kUnsupportedFeature in a build
// without eqmesh_metrics.
StatusOr<double> MeasureMeshPsnr(const Mesh& mesh, const Mesh& original, uint64_t samples = 0);
// The stream decoded within `max_triangles` (0: every triangle of every level).
StatusOr<double> MeasureStreamPsnr(const std::vector<uint8_t>& stream, const Mesh& original, uint64_t samples = 0,
                                   uint64_t max_triangles = 0);

}  // namespace eqmesh

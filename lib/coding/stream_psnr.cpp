#include "coding/stream_psnr.h"

#include "coding/decoder.h"
#ifdef EQMESH_HAVE_METRICS
#include "metrics/surface_distance.h"
#endif

namespace eqmesh {

StatusOr<double> MeasureMeshPsnr(const Mesh& mesh, const Mesh& original, uint64_t samples) {
#ifdef EQMESH_HAVE_METRICS
  CompareOptions compare;
  compare.samples = samples;
  EQMESH_ASSIGN_OR_RETURN(const SurfaceDistance d, CompareSurfaces(original, mesh, compare));
  return d.psnr_db;
#else
  (void)mesh, (void)original, (void)samples;
  return UnsupportedFeature("measuring PSNR needs eqmesh_metrics, which this build lacks");
#endif
}

StatusOr<double> MeasureStreamPsnr(const std::vector<uint8_t>& stream, const Mesh& original, uint64_t samples,
                                   uint64_t max_triangles) {
  DecodeOptions options;
  options.max_triangles = max_triangles;
  EQMESH_ASSIGN_OR_RETURN(const Mesh decoded, Decode(stream.data(), stream.size(), options));
  return MeasureMeshPsnr(decoded, original, samples);
}

}  // namespace eqmesh

#include "coding/stream_psnr.h"

#include "coding/decoder.h"
#ifdef EQMESH_HAVE_METRICS
#include <mutex>

#include "metrics/surface_distance.h"
#endif

namespace eqmesh {

#ifdef EQMESH_HAVE_METRICS
struct PreparedOriginal::Series {
  std::mutex lock;
  ApproximationSeries trees;
};
#endif

StatusOr<std::shared_ptr<const PreparedOriginal>> PrepareOriginal(const Mesh& original) {
#ifdef EQMESH_HAVE_METRICS
  EQMESH_ASSIGN_OR_RETURN(ReferenceSurface reference, ReferenceSurface::Build(original));
  auto prepared = std::make_shared<PreparedOriginal>();
  prepared->mesh = &original;
  prepared->reference = std::make_shared<const ReferenceSurface>(std::move(reference));
  prepared->series = std::make_shared<PreparedOriginal::Series>();
  return std::shared_ptr<const PreparedOriginal>(std::move(prepared));
#else
  (void)original;
  return UnsupportedFeature("measuring PSNR needs eqmesh_metrics, which this build lacks");
#endif
}

StatusOr<double> MeasureMeshPsnr(const Mesh& mesh, const Mesh& original, uint64_t samples,
                                 const PreparedOriginal* prepared) {
#ifdef EQMESH_HAVE_METRICS
  CompareOptions compare;
  compare.samples = samples;
  if (prepared != nullptr && prepared->mesh == &original && prepared->reference != nullptr) {
    std::unique_lock<std::mutex> series;
    if (prepared->series != nullptr) series = std::unique_lock<std::mutex>(prepared->series->lock, std::try_to_lock);
    ApproximationSeries* trees = series.owns_lock() ? &prepared->series->trees : nullptr;
    EQMESH_ASSIGN_OR_RETURN(const SurfaceDistance d, prepared->reference->Compare(mesh, compare, trees));
    return d.psnr_db;
  }
  EQMESH_ASSIGN_OR_RETURN(const SurfaceDistance d, CompareSurfaces(original, mesh, compare));
  return d.psnr_db;
#else
  (void)mesh, (void)original, (void)samples, (void)prepared;
  return UnsupportedFeature("measuring PSNR needs eqmesh_metrics, which this build lacks");
#endif
}

StatusOr<Mesh> DecodeForMeasure(const std::vector<uint8_t>& stream, uint64_t max_triangles) {
  DecodeOptions options;
  options.max_triangles = max_triangles;
  return Decode(stream.data(), stream.size(), options);
}

StatusOr<double> MeasureStreamPsnr(const std::vector<uint8_t>& stream, const Mesh& original, uint64_t samples,
                                   uint64_t max_triangles, const PreparedOriginal* prepared) {
  EQMESH_ASSIGN_OR_RETURN(const Mesh decoded, DecodeForMeasure(stream, max_triangles));
  return MeasureMeshPsnr(decoded, original, samples, prepared);
}

}  // namespace eqmesh

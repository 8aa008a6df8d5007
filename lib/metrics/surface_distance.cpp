// CompareSurfaces: see surface_distance.h for the papers and departures.
//
// Each direction draws `samples` stratified area-uniform points (AreaSampler),
// in blocks of kBlockSize. A block's random stream depends only on (seed,
// direction, block index) and its sums are kept in its own slot; the slots are
// added in block order. That is what makes the doubles identical for any
// thread count. Within a block the samples are in face order, hence spatially
// coherent: the previous sample's closest face gives an upper bound that lets
// the BVH search prune early. In a series of measurements (ApproximationSeries)
// each sample also tries the face it found the last time (the same point of the
// original, or nearly the same point of an approximation that only moved), and
// the approximation's tree is refitted instead of built: an encoder's PSNR
// search measures every trial stream, and the trials of one level count share
// one connectivity. Hints and tree shapes only change how fast the exact
// answer is found.
//
// Distances below kNumericalZero x (larger bbox diagonal) are counted as 0:
// re-projecting a sample onto the very triangle it was drawn from leaves
// ~1e-16 relative rounding, and a mesh compared with itself must give
// exactly 0 and PSNR +inf. Anything that small is below the precision of the
// coordinates themselves.
#include "metrics/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "mesh/triangle_bvh.h"
#include "metrics/area_sampler.h"
#include "core/parallel_blocks.h"

namespace eqmesh {
namespace {

constexpr uint64_t kBlockSize = 4096;
constexpr int kMaxThreads = 1024;
constexpr double kNumericalZero = 1e-12;

struct DirectionStats {
  double rms = 0.0, mean = 0.0, max = 0.0;
};

struct BlockSums {
  double sum_d2 = 0.0, sum_d = 0.0, max_d = 0.0;
};

// Squared distance from p to face f of `to`.
double SquaredDistanceToFace(const Mesh& to, uint32_t f, const Vec3& p) {
  const Face& t = to.faces[f];
  std::array<double, 3> bary;
  const Vec3 q = ClosestPointOnTriangle(p, to.positions[t[0]], to.positions[t[1]], to.positions[t[2]], &bary);
  return (q - p).squaredNorm();
}

// Squared distance from p to `to`, searched within the nearer of the hints'
// faces: the previous sample's closest face (*hint) and, in a series, this
// sample's closest face the last time (*own). A hint only bounds the search,
// so the distance is the unbounded search's. Updates both hints.
double SquaredDistanceWithHint(const TriangleBvh& bvh, const Mesh& to, const Vec3& p, uint32_t* hint,
                               uint32_t* own) {
  double hint_d2 = std::numeric_limits<double>::infinity();
  uint32_t hint_face = kNoFace;
  for (const uint32_t* h : {hint, own}) {
    if (h == nullptr || *h == kNoFace || *h >= to.faces.size()) continue;
    const double d2 = SquaredDistanceToFace(to, *h, p);
    if (d2 < hint_d2) hint_d2 = d2, hint_face = *h;
  }
  // Inclusive of the hint face itself.
  const double bound = hint_face == kNoFace ? std::numeric_limits<double>::infinity()
                                            : std::sqrt(hint_d2) * (1.0 + 1e-9);
  const ClosestPointResult r = bvh.ClosestPoint(p, bound);
  const bool searched = r.found() && r.squared_distance <= hint_d2;
  *hint = searched ? r.face : hint_face;
  if (own != nullptr) *own = *hint;
  return searched ? r.squared_distance : hint_d2;
}

struct DirectionInput {
  const AreaSampler& from;
  const TriangleBvh& bvh;
  const Mesh& to;
  uint64_t samples, seed, direction;
  double zero_distance;  // distances at or below this count as 0
  uint32_t* sample_faces = nullptr;  // per sample, its closest face the last time (a series), or null
};

BlockSums MeasureBlock(const DirectionInput& in, uint64_t block) {
  const uint64_t first = block * kBlockSize;
  const uint64_t count = std::min(kBlockSize, in.samples - first);
  SampleRng rng = SampleRng::ForBlock(in.seed, in.direction, block);
  std::vector<Vec3> points;
  points.reserve(count);
  in.from.Sample(in.samples, first, count, &rng, &points);
  BlockSums sums;
  uint32_t hint = kNoFace;
  for (uint64_t i = 0; i < points.size(); ++i) {
    uint32_t* own = in.sample_faces != nullptr ? in.sample_faces + first + i : nullptr;
    double d2 = SquaredDistanceWithHint(in.bvh, in.to, points[i], &hint, own);
    double d = std::sqrt(d2);
    if (d <= in.zero_distance) d = d2 = 0.0;
    sums.sum_d2 += d2;
    sums.sum_d += d;
    sums.max_d = std::max(sums.max_d, d);
  }
  return sums;
}

DirectionStats MeasureDirection(const DirectionInput& in, int threads) {
  const uint64_t num_blocks = (in.samples + kBlockSize - 1) / kBlockSize;
  std::vector<BlockSums> blocks(num_blocks);
  ForEachBlock(num_blocks, threads, [&](uint64_t b) { blocks[b] = MeasureBlock(in, b); });
  BlockSums total;
  for (const BlockSums& s : blocks) {  // block order: thread-count independent
    total.sum_d2 += s.sum_d2;
    total.sum_d += s.sum_d;
    total.max_d = std::max(total.max_d, s.max_d);
  }
  const double n = static_cast<double>(in.samples);
  return {std::sqrt(total.sum_d2 / n), total.sum_d / n, total.max_d};
}

Status CheckOptions(const CompareOptions& options) {
  if (options.samples > kMaxCompareSamples)
    return ResourceLimit("samples = " + std::to_string(options.samples) + " exceeds the limit of " +
                         std::to_string(kMaxCompareSamples) + " per direction");
  if (options.threads < 0 || options.threads > kMaxThreads)
    return InvalidArgument("threads = " + std::to_string(options.threads) + " is not in 0.." +
                           std::to_string(kMaxThreads));
  return Status::Ok();
}

// Inputs of ordinary size are measured as they are, unscaled;
// beyond these scales areas and squared distances would over- or underflow, so
// they are measured at PowerOfTwoUnitScale. Returns 1 for "as they are".
constexpr double kLargestUnscaled = 0x1p32, kSmallestUnscaled = 0x1p-32;
double MeasuringScale(const Mesh& mesh) {
  const double scale = PowerOfTwoUnitScale(mesh);
  return scale <= kLargestUnscaled && scale >= kSmallestUnscaled ? 1.0 : scale;
}

Mesh Scaled(const Mesh& mesh, double scale) {
  Mesh out = mesh;
  for (Vec3& p : out.positions) p *= scale;
  return out;
}

// The original at the scale it is measured at, with what measuring against it needs.
struct ReferenceParts {
  double scale = 1.0;  // MeasuringScale of the original
  Mesh mesh;           // the original, multiplied by `scale`
  AreaSampler sampler;
  TriangleBvh bvh;
  double diagonal = 0.0;  // of `mesh`
};

StatusOr<ReferenceParts> PrepareReference(const Mesh& a) {
  ReferenceParts r;
  r.scale = MeasuringScale(a);
  r.mesh = r.scale == 1.0 ? a : Scaled(a, r.scale);
  auto sampler = AreaSampler::Build(r.mesh);
  if (!sampler.ok()) return sampler.status().WithContext("original mesh");
  auto bvh = TriangleBvh::Build(r.mesh);
  if (!bvh.ok()) return bvh.status().WithContext("original mesh");
  r.sampler = std::move(*sampler);
  r.bvh = std::move(*bvh);
  r.diagonal = BoundingBoxDiagonal(r.mesh);
  return r;
}

}  // namespace

struct ApproximationSeries::State {
  std::vector<Face> faces;  // of the mesh `bvh` was last fitted to
  std::optional<TriangleBvh> bvh;
  // What the last measurement's samples found, per sample: the closest face of
  // the approximation to each sample of the original (valid while the faces
  // stay the same) and of the original to each sample of the approximation
  // (any face of it is a valid hint). Kept for one original, sample count and
  // seed: the original's samples are then the same points again.
  const void* original = nullptr;
  uint64_t samples = 0, seed = 0;
  std::vector<uint32_t> to_approximation, to_original;
};

ApproximationSeries::ApproximationSeries() : state_(std::make_unique<State>()) {}
ApproximationSeries::~ApproximationSeries() = default;
ApproximationSeries::ApproximationSeries(ApproximationSeries&&) noexcept = default;
ApproximationSeries& ApproximationSeries::operator=(ApproximationSeries&&) noexcept = default;

namespace {

// The search tree over `b`: the series' tree refitted when it was last fitted
// to b's faces (*refitted), else a new one (kept in the series when there is
// one, else in *own).
StatusOr<const TriangleBvh*> TreeOver(const Mesh& b, ApproximationSeries::State* series,
                                      std::optional<TriangleBvh>* own, bool* refitted) {
  *refitted = series != nullptr && series->bvh && series->faces == b.faces && series->bvh->Refit(b).ok();
  if (*refitted) return &*series->bvh;
  if (series != nullptr) series->bvh.reset();  // not two trees in memory at once
  auto built = TriangleBvh::Build(b);
  if (!built.ok()) return built.status();
  if (series == nullptr) {
    own->emplace(std::move(*built));
    return &**own;
  }
  series->bvh.emplace(std::move(*built));
  series->faces = b.faces;
  return &*series->bvh;
}

// Readies the series' per-sample faces for a measurement of `samples` per
// direction against `original`; those found on an approximation with other
// faces are dropped.
void ReadySampleFaces(ApproximationSeries::State* series, const void* original, uint64_t samples, uint64_t seed,
                      bool same_faces) {
  const bool same_samples = series->original == original && series->samples == samples && series->seed == seed;
  if (!same_samples || !same_faces) series->to_approximation.assign(samples, kNoFace);
  if (!same_samples) series->to_original.assign(samples, kNoFace);
  series->original = original;
  series->samples = samples;
  series->seed = seed;
}

// `b` at the reference's scale against it; lengths at that scale.
StatusOr<SurfaceDistance> CompareAtOwnScale(const ReferenceParts& a, const Mesh& b, const CompareOptions& options,
                                            ApproximationSeries::State* series) {
  auto sampler_b = AreaSampler::Build(b);
  if (!sampler_b.ok()) return sampler_b.status().WithContext("other mesh");
  std::optional<TriangleBvh> own;
  bool refitted = false;
  auto tree = TreeOver(b, series, &own, &refitted);
  if (!tree.ok()) return tree.status().WithContext("other mesh");
  const TriangleBvh* bvh_b = *tree;

  SurfaceDistance r;
  r.samples = options.samples > 0 ? options.samples : DefaultSampleCount(a.mesh);
  r.bbox_diagonal = a.diagonal;
  const double zero = kNumericalZero * std::max(r.bbox_diagonal, BoundingBoxDiagonal(b));
  uint32_t* to_b = nullptr;
  uint32_t* to_a = nullptr;
  if (series != nullptr) {
    ReadySampleFaces(series, &a, r.samples, options.seed, refitted);
    to_b = series->to_approximation.data();
    to_a = series->to_original.data();
  }
  const DirectionStats ab =
      MeasureDirection({a.sampler, *bvh_b, b, r.samples, options.seed, 0, zero, to_b}, options.threads);
  const DirectionStats ba =
      MeasureDirection({*sampler_b, a.bvh, a.mesh, r.samples, options.seed, 1, zero, to_a}, options.threads);
  r.rms_ab = ab.rms;
  r.rms_ba = ba.rms;
  r.rms = std::max(ab.rms, ba.rms);
  r.mean_ab = ab.mean;
  r.mean_ba = ba.mean;
  r.mean = std::max(ab.mean, ba.mean);
  r.hausdorff_ab = ab.max;
  r.hausdorff_ba = ba.max;
  r.hausdorff = std::max(ab.max, ba.max);
  r.psnr_db = PsnrDb(r.bbox_diagonal, r.rms);
  return r;
}

}  // namespace

uint64_t DefaultSampleCount(const Mesh& original) {
  // Measured (armadillo_50k vs its 0.1 %-of-diagonal noisy copy, 5 seeds):
  // PSNR spread 0.018 dB at 100k samples, 0.010 dB at 300k, 0.003 dB at 1M.
  // 1M leaves a wide margin under the +-0.1 dB target even for errors
  // concentrated in a small area; 10 per vertex keeps small features of big
  // originals sampled; the 20M cap bounds the time on huge inputs. The
  // approximation's vertex count does not enter: a semi-regular remesh carries
  // up to 64x the original's vertices, uniformly spread, and its features are
  // the original's (horse at 6 levels: 5.86M samples per direction would take
  // 4.9 s, 1M 1.75 s, spread between seeds 0.05 and 0.06 dB at 86 dB).
  return std::clamp<uint64_t>(10 * static_cast<uint64_t>(original.positions.size()), 1'000'000, 20'000'000);
}

Status ValidateForCompare(const Mesh& mesh) {
  // AreaSampler::Build makes every check the meter needs (and TriangleBvh's),
  // at the scale CompareSurfaces measures at.
  const double scale = MeasuringScale(mesh);
  return AreaSampler::Build(scale == 1.0 ? mesh : Scaled(mesh, scale)).status();
}

double PsnrDb(double bbox_diagonal, double rms) {
  if (rms == 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(bbox_diagonal / rms);
}

struct ReferenceSurface::Prepared : ReferenceParts {
  explicit Prepared(ReferenceParts parts) : ReferenceParts(std::move(parts)) {}
};

StatusOr<ReferenceSurface> ReferenceSurface::Build(const Mesh& a) {
  EQMESH_ASSIGN_OR_RETURN(ReferenceParts parts, PrepareReference(a));
  ReferenceSurface reference;
  reference.prepared_ = std::make_shared<const Prepared>(std::move(parts));
  return reference;
}

StatusOr<SurfaceDistance> ReferenceSurface::Compare(const Mesh& b, const CompareOptions& options,
                                                    ApproximationSeries* series) const {
  EQMESH_RETURN_IF_ERROR(CheckOptions(options));
  const double scale = prepared_->scale;
  ApproximationSeries::State* state = series != nullptr ? series->state_.get() : nullptr;
  if (scale == 1.0) return CompareAtOwnScale(*prepared_, b, options, state);
  // Both by the same power of two (exact), the lengths back by its inverse.
  EQMESH_ASSIGN_OR_RETURN(SurfaceDistance r, CompareAtOwnScale(*prepared_, Scaled(b, scale), options, state));
  for (double* length : {&r.bbox_diagonal, &r.rms_ab, &r.rms_ba, &r.rms, &r.mean_ab, &r.mean_ba, &r.mean,
                         &r.hausdorff_ab, &r.hausdorff_ba, &r.hausdorff}) {
    *length /= scale;
  }
  return r;
}

StatusOr<SurfaceDistance> CompareSurfaces(const Mesh& a, const Mesh& b,
                                          const CompareOptions& options) {
  EQMESH_RETURN_IF_ERROR(CheckOptions(options));
  EQMESH_ASSIGN_OR_RETURN(const ReferenceSurface reference, ReferenceSurface::Build(a));
  return reference.Compare(b, options);
}

}  // namespace eqmesh

// Representation choice: see representation_choice.h.
#include "coding/representation_choice.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "coding/base_size_walk.h"
#include "coding/bitstream_shared.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "remesh/quadric_simplification.h"
#include "remesh/remesh.h"

namespace eqmesh {
namespace {

// `surface` as a semi-regular mesh with no levels: its base.
StatusOr<SemiRegularMesh> WithoutLevels(Mesh surface) {
  SemiRegularMesh out;
  EQMESH_ASSIGN_OR_RETURN(out.hierarchy, SemiRegularHierarchy::Build(static_cast<uint32_t>(surface.positions.size()),
                                                                     std::move(surface.faces), 0));
  out.positions = std::move(surface.positions);
  return out;
}

}  // namespace

StatusOr<SemiRegularMesh> AsIsMesh(const Mesh& input, bool repair) {
  // The remesher's preparation (unreferenced vertices dropped, manifold checks or
  // repair) with no simplification and no levels; then the small components it
  // sets aside join the base, which codes them better than the kept chunk's fixed
  // 20-bit grid.
  RemeshOptions options;
  options.levels = 0;
  options.base_vertices = static_cast<int>(input.positions.size());
  options.repair = repair;
  RemeshReport report;
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh mesh, Remesh(input, options, &report));
  if (mesh.kept_exactly.faces.empty()) return mesh;
  return WithoutLevels(ExtractLevel(std::move(mesh), 0));  // the kept components appended to the base
}

bool AsIsFitsIn(const SemiRegularMesh& as_is, size_t bytes) {
  const double vertices = static_cast<double>(as_is.positions.size());
  const auto connectivity = CompactConnectivityBytes(ExtractLevel(as_is, 0));
  // A mesh the compact chunk cannot hold goes to Draco: about 3 bits per vertex.
  const double connectivity_bits = connectivity.ok() ? 8.0 * static_cast<double>(*connectivity) : 3.0 * vertices;
  return 8.0 * static_cast<double>(bytes) >= connectivity_bits + kAsIsMinPositionBits * vertices;
}

namespace {

bool Targeted(const EncodeOptions& options) { return options.target_psnr > 0 || options.target_bpv > 0; }

bool OutOfReach(const Status& status) { return status.code() == StatusCode::kTargetOutOfReach; }

// Both representations short of a PSNR target: one line naming what each reached.
// The as-is side's uncoded ceiling is the input's own mesh, not a remesh.
Status BothOutOfReach(const Status& remeshed, const Status& as_is) {
  std::string reached = OutOfReachReached(as_is);
  const std::string ceiling = kUncodedCeiling;
  if (reached.compare(0, ceiling.size(), ceiling) == 0) reached.replace(0, ceiling.size(), "the mesh itself, uncoded,");
  return Status(StatusCode::kTargetOutOfReach, remeshed.message() + "; coded as is, " + reached);
}

// True when `b` (as is) should replace `a` (remeshed), both encoded with a target.
bool AsIsIsBetter(const EncodeOptions& options, const EncodeReport& a, const EncodeReport& b) {
  if (options.target_psnr > 0) return b.total_bytes < a.total_bytes;
  return b.psnr_db > a.psnr_db;
}

// Every component too small to remesh (a cube, a low-poly prop): no normal mesh
// exists, and the input as is is the only representation.
bool NothingRemeshed(const SemiRegularMesh& remeshed) {
  return remeshed.hierarchy.NumVertices(0) == 0 && !remeshed.kept_exactly.faces.empty();
}

// Whether the as-is stream is worth encoding after the remeshed one, before the
// size test (AsIsFitsIn). Without a target too: a low-poly asset's normal mesh
// spends many times the bytes of the input coded as is, whether decoded whole
// (the remesh follows its facets only with levels far finer than the input) or
// within its own triangle count (where it cannot follow them at all).
bool WorthTrying(const EncodeOptions& options, const RepresentationOptions& representation,
                 const SemiRegularMesh& remeshed, const StatusOr<std::vector<uint8_t>>& stream) {
  if (!representation.allow_as_is || options.original == nullptr) return false;
  // A base chunk holds at most kMaxBaseVertices (ext_spec A.3).
  if (options.original->positions.size() > bitstream::kMaxBaseVertices) return false;
  return stream.ok() || OutOfReach(stream.status()) || NothingRemeshed(remeshed);
}

// The remeshed stream's PSNR, measured if the encode did not (a bare lambda
// without --measure), for the comparison.
Status EnsureMeasured(const std::vector<uint8_t>& stream, const EncodeOptions& options, EncodeReport* report) {
  if (report->psnr_measured) return Status::Ok();
  EQMESH_ASSIGN_OR_RETURN(report->psnr_db, MeasureEncodedPsnr(stream, options, 0));
  report->psnr_measured = true;
  return Status::Ok();
}

struct AsIsCandidate {
  StatusOr<std::vector<uint8_t>> stream = std::vector<uint8_t>();
  EncodeReport report;
  LevelCountReport levels;
  size_t vertices = 0;  // of the mesh coded
  bool better = false;  // replaces the remeshed stream
};

AsIsCandidate EncodeAsIs(const SemiRegularMesh& as_is_mesh, const EncodeOptions& options) {
  AsIsCandidate c;
  c.stream = EncodeChoosingLevels(as_is_mesh, options, &c.report, &c.levels);
  c.vertices = as_is_mesh.positions.size();
  return c;
}

// The as-is mesh simplified to `share` of its vertices (none: the
// simplification stopped short of one vertex fewer).
std::optional<SemiRegularMesh> SimplifiedAsIs(const SemiRegularMesh& as_is, double share) {
  const size_t n = as_is.positions.size();
  const auto target = static_cast<size_t>(std::llround(share * static_cast<double>(n)));
  auto simplified = SimplifyByQuadrics(ExtractLevel(as_is, 0), target);
  if (!simplified.ok() || simplified->positions.size() >= n) return std::nullopt;
  auto out = WithoutLevels(std::move(simplified).value());
  if (!out.ok()) return std::nullopt;
  return std::move(out).value();
}

// Whether `a` replaces `b` among as-is candidates for a target.
bool BeatsForTarget(const EncodeOptions& options, const AsIsCandidate& a, const AsIsCandidate& b) {
  if (!a.stream.ok()) return false;
  return !b.stream.ok() || AsIsIsBetter(options, b.report, a.report);
}

// With a target: `best` (the input as is, coded for it), then the input
// simplified (kSimplifyShare steps, see the header); the best of those tried.
AsIsCandidate WalkSimplified(const SemiRegularMesh& as_is, const EncodeOptions& options, AsIsCandidate best) {
  if (!best.stream.ok()) return best;  // a simplified mesh reaches no further
  const SemiRegularMesh* from = &as_is;
  std::optional<SemiRegularMesh> kept;
  for (int step = 0; step < kMaxSimplifySteps; ++step) {
    std::optional<SemiRegularMesh> mesh = SimplifiedAsIs(*from, kSimplifyShare);
    if (!mesh) break;
    AsIsCandidate c = EncodeAsIs(*mesh, ToBeat(options, best.stream, best.report));
    if (!BeatsForTarget(options, c, best)) {
      if (step > 0) break;
      std::optional<SemiRegularMesh> half = SimplifiedAsIs(as_is, std::sqrt(kSimplifyShare));
      if (!half) break;
      AsIsCandidate h = EncodeAsIs(*half, ToBeat(options, best.stream, best.report));
      if (BeatsForTarget(options, h, best)) best = std::move(h);
      break;
    }
    best = std::move(c);
    kept = std::move(mesh);
    from = &*kept;
  }
  return best;
}

AsIsCandidate EncodeBestAsIs(const SemiRegularMesh& as_is, const EncodeOptions& options) {
  return WalkSimplified(as_is, options, EncodeAsIs(as_is, options));
}

// Without a target. Below the floor the higher PSNR at the caller's lambda
// wins. Above it the as-is stream at that lambda wins where it is neither
// larger nor worse (then simplified where that keeps its PSNR in fewer bytes);
// failing that, the as-is stream searched for the remeshed one's PSNR (and
// simplified likewise) wins where it is no larger. (Streams at one lambda sit at
// unrelated points of the two rate-distortion curves: a 66-vertex cylinder as
// is, 286 B at 76.3 dB; its normal mesh within 128 triangles, 4,407 B at 77.9.)
StatusOr<AsIsCandidate> UntargetedAsIs(const SemiRegularMesh& as_is_mesh, const EncodeOptions& options,
                                       const RepresentationOptions& representation,
                                       const std::vector<uint8_t>& stream, EncodeReport* remeshed) {
  // Every stream here is measured against the same original: prepared once
  // (an encode at a bare lambda without --measure has not prepared it).
  EncodeOptions measured = options;
  measured.measure_psnr = true;
  measured = WithPreparedOriginal(measured);
  EQMESH_RETURN_IF_ERROR(EnsureMeasured(stream, measured, remeshed));
  AsIsCandidate at_lambda = EncodeAsIs(as_is_mesh, measured);
  if (!at_lambda.stream.ok()) return at_lambda;
  const EncodeReport& r = at_lambda.report;
  if (remeshed->psnr_db < representation.floor_db) {
    at_lambda.better = r.psnr_db > remeshed->psnr_db;
    return at_lambda;
  }
  if (r.psnr_db >= remeshed->psnr_db && r.total_bytes <= remeshed->total_bytes) {
    // The same quality from fewer vertices, where the input has more than that
    // quality needs.
    EncodeOptions same_quality = measured;
    same_quality.target_psnr = r.psnr_db;
    AsIsCandidate kept = WalkSimplified(as_is_mesh, same_quality, std::move(at_lambda));
    kept.better = true;
    return kept;
  }
  measured.target_psnr = remeshed->psnr_db;
  AsIsCandidate at_quality = EncodeBestAsIs(as_is_mesh, measured);
  at_quality.better = at_quality.stream.ok() && at_quality.report.total_bytes <= remeshed->total_bytes;
  // Out of reach as is (a PSNR past its quantizer's finest step): the stream at
  // the lambda stands for the representation in the report.
  return at_quality.stream.ok() ? std::move(at_quality) : std::move(at_lambda);
}

// Where the remesher's stream met its target or fell short of it, the base-size
// walk (base_size_walk.h) from it; the best replaces it.
void TryOtherBaseSizes(const EncodeOptions& options, const RemeshOptions& remesh,
                       StatusOr<std::vector<uint8_t>>* stream, EncodeReport* report, LevelCountReport* levels,
                       RepresentationReport* c) {
  if (!stream->ok() && !OutOfReach(stream->status())) return;
  BaseSizeTry first;
  first.base_vertices = c->remeshed_base_vertices;
  first.stream = std::move(*stream);
  first.report = *report;
  first.levels = std::move(*levels);
  BaseSizeTry best = WalkBaseSizes(*options.original, remesh, options, std::move(first), &c->base_sizes_tried);
  *stream = std::move(best.stream);
  *report = best.report;
  *levels = std::move(best.levels);
  c->remeshed_base_vertices = best.base_vertices;
  if (best.remesh.base_vertices > 0) c->walked_remesh = best.remesh;  // a try won
}

}  // namespace

StatusOr<std::vector<uint8_t>> EncodeChoosingRepresentation(const SemiRegularMesh& remeshed,
                                                            const EncodeOptions& requested,
                                                            const RepresentationOptions& representation,
                                                            EncodeReport* report, LevelCountReport* levels,
                                                            RepresentationReport* choice) {
  const EncodeOptions options = WithPreparedOriginal(requested);
  RepresentationReport local;
  RepresentationReport& c = choice ? *choice : local;
  c = RepresentationReport();
  c.nothing_remeshed = NothingRemeshed(remeshed);
  EncodeReport remeshed_report;
  LevelCountReport remeshed_levels;
  auto stream = EncodeChoosingLevels(remeshed, options, &remeshed_report, &remeshed_levels);
  c.remeshed_base_vertices = remeshed.hierarchy.NumVertices(0);
  // Whether the as-is representation has room is judged against the remesher's
  // own stream: the walk's smaller one would shut out a simplified as-is stream
  // smaller still (bull at 70 dB: 7,372 B walked, 5,653 B simplified as is).
  const bool first_ok = stream.ok();
  const size_t first_bytes = first_ok ? stream->size() : 0;
  if (representation.remesh != nullptr && !c.nothing_remeshed && BaseWalkApplies(options)) {
    TryOtherBaseSizes(options, *representation.remesh, &stream, &remeshed_report, &remeshed_levels, &c);
  }
  if (stream.ok()) {
    c.remeshed_bytes = stream->size();
    c.remeshed_psnr_db = remeshed_report.psnr_db;
  }
  if (WorthTrying(options, representation, remeshed, stream)) {
    auto as_is_mesh = AsIsMesh(*options.original, representation.repair);
    // With a bpv target the as-is stream gets the same bytes; with a PSNR target it
    // must come in under the remeshed stream's; below a floor, size does not decide.
    const double bpv_bytes = options.target_bpv * static_cast<double>(options.input_vertices) / 8.0;
    // Without a target, it must come in under it too unless the remeshed stream
    // missed the floor (AsIsIsBetter).
    const bool floor_missed = remeshed_report.psnr_measured && remeshed_report.psnr_db < representation.floor_db;
    const size_t budget = options.target_bpv > 0                                          ? static_cast<size_t>(bpv_bytes)
                          : first_ok && (options.target_psnr > 0 || !floor_missed)    ? first_bytes
                                                                                          : SIZE_MAX;
    if (as_is_mesh.ok() && (!first_ok || AsIsFitsIn(*as_is_mesh, budget))) {
      c.tried_as_is = true;
      AsIsCandidate as_is;
      if (!Targeted(options) && stream.ok()) {
        EQMESH_ASSIGN_OR_RETURN(as_is, UntargetedAsIs(*as_is_mesh, options, representation, *stream, &remeshed_report));
        c.remeshed_psnr_db = remeshed_report.psnr_db;
      } else {
        as_is = EncodeBestAsIs(*as_is_mesh, options);
        as_is.better = as_is.stream.ok() &&
                       (!stream.ok() || AsIsIsBetter(options, remeshed_report, as_is.report));
      }
      if (as_is.stream.ok()) {
        c.as_is_bytes = as_is.stream->size();
        c.as_is_psnr_db = as_is.report.psnr_db;
        c.as_is_vertices = as_is.vertices;
      }
      if (as_is.better) {
        c.as_is = true;
        if (report) *report = as_is.report;
        if (levels) *levels = std::move(as_is.levels);
        return std::move(as_is.stream);
      }
      if (!stream.ok() && OutOfReach(stream.status()) && !as_is.stream.ok() && OutOfReach(as_is.stream.status())) {
        return BothOutOfReach(stream.status(), as_is.stream.status());
      }
      // With no normal mesh, the input as is was the only candidate: its failure
      // (a target out of reach) is the one to report.
      if (c.nothing_remeshed && !as_is.stream.ok()) return as_is.stream.status();
    }
  }
  if (!stream.ok()) return stream.status();
  if (report) *report = remeshed_report;
  if (levels) *levels = std::move(remeshed_levels);
  return stream;
}

}  // namespace eqmesh

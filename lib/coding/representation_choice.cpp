// Representation choice: see representation_choice.h.
#include "coding/representation_choice.h"

#include <cstdint>
#include <string>
#include <utility>

#include "coding/bitstream_shared.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "remesh/remesh.h"

namespace eqmesh {

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
  Mesh base;
  base.positions = std::move(mesh.positions);
  base.faces = mesh.hierarchy.BaseFaces();
  AppendKeptComponents(mesh.kept_exactly, &base);
  SemiRegularMesh out;
  EQMESH_ASSIGN_OR_RETURN(out.hierarchy, SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                                                     std::move(base.faces), 0));
  out.positions = std::move(base.positions);
  return out;
}

bool AsIsFitsIn(const SemiRegularMesh& as_is, size_t bytes) {
  const double vertices = static_cast<double>(as_is.positions.size());
  Mesh surface;
  surface.positions = as_is.positions;
  surface.faces = as_is.hierarchy.BaseFaces();
  const auto connectivity = CompactConnectivityBytes(surface);
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

// True when `b` (as is) should replace `a` (remeshed), both encoded.
bool AsIsIsBetter(const EncodeOptions& options, const EncodeReport& a, const EncodeReport& b) {
  if (options.target_psnr > 0) return b.total_bytes < a.total_bytes;
  return b.psnr_db > a.psnr_db;
}

// Whether the as-is stream is worth encoding after the remeshed one, before the
// size test (AsIsFitsIn).
bool WorthTrying(const EncodeOptions& options, const RepresentationOptions& representation,
                 const StatusOr<std::vector<uint8_t>>& stream, const EncodeReport& report) {
  if (!representation.allow_as_is || options.original == nullptr) return false;
  // A base chunk holds at most kMaxBaseVertices (ext_spec A.3).
  if (options.original->positions.size() > bitstream::kMaxBaseVertices) return false;
  const bool out_of_reach = !stream.ok() && OutOfReach(stream.status());
  if (Targeted(options)) return out_of_reach || stream.ok();
  return representation.floor_db > 0 && options.measure_psnr &&
         (out_of_reach || (stream.ok() && report.psnr_db < representation.floor_db));
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
  EncodeReport remeshed_report;
  LevelCountReport remeshed_levels;
  auto stream = EncodeChoosingLevels(remeshed, options, &remeshed_report, &remeshed_levels);
  if (stream.ok()) {
    c.remeshed_bytes = stream->size();
    c.remeshed_psnr_db = remeshed_report.psnr_db;
  }
  if (WorthTrying(options, representation, stream, remeshed_report)) {
    auto as_is_mesh = AsIsMesh(*options.original, representation.repair);
    // With a bpv target the as-is stream gets the same bytes; with a PSNR target it
    // must come in under the remeshed stream's; below a floor, size does not decide.
    const double bpv_bytes = options.target_bpv * static_cast<double>(options.input_vertices) / 8.0;
    const size_t budget = options.target_bpv > 0                    ? static_cast<size_t>(bpv_bytes)
                          : options.target_psnr > 0 && stream.ok() ? stream->size()
                                                                    : SIZE_MAX;
    if (as_is_mesh.ok() && (!stream.ok() || AsIsFitsIn(*as_is_mesh, budget))) {
      c.tried_as_is = true;
      EncodeReport as_is_report;
      LevelCountReport as_is_levels;
      auto as_is = EncodeChoosingLevels(*as_is_mesh, options, &as_is_report, &as_is_levels);
      if (as_is.ok()) {
        c.as_is_bytes = as_is->size();
        c.as_is_psnr_db = as_is_report.psnr_db;
      }
      if (as_is.ok() && (!stream.ok() || AsIsIsBetter(options, remeshed_report, as_is_report))) {
        c.as_is = true;
        if (report) *report = as_is_report;
        if (levels) *levels = std::move(as_is_levels);
        return as_is;
      }
      if (!stream.ok() && OutOfReach(stream.status()) && !as_is.ok() && OutOfReach(as_is.status())) {
        return BothOutOfReach(stream.status(), as_is.status());
      }
    }
  }
  if (!stream.ok()) return stream.status();
  if (report) *report = remeshed_report;
  if (levels) *levels = std::move(remeshed_levels);
  return stream;
}

}  // namespace eqmesh

// Closed-loop encoder (see encoder.h for the papers and departures).
//
// The exact loop, unlifted transform:
//   1. base chunk: Draco-code the level-0 positions at the R-D chosen depth; the
//      semi-regular mesh is renumbered to the order the chunk decodes to;
//   2. P_0 = the Draco-decoded base positions (what the decoder has);
//   3. for j = 0..J-1: prediction and frames from P_j only; detail = true odd
//      position - prediction, in the local frame; the level coder quantizes it
//      and returns the reconstruction r; P_{j+1} = P_j + (prediction + r in world
//      coordinates) -- exactly the decoder's computation, so the next level's
//      details also correct this level's quantization error where it matters.
#include "coding/encoder.h"

#include <cmath>
#include <optional>

#include "coding/base_influence.h"
#include "coding/base_mesh_encoder.h"
#include "coding/decoder.h"
#include "coding/level_encoder.h"
#include "coding/level_synthesis.h"
#include "coding/rate_control.h"
#include "coding/semi_regular_reorder.h"
#include "coding/stream_header.h"

#ifdef EQMESH_HAVE_METRICS
#include "metrics/surface_distance.h"
#endif

namespace eqmesh {
namespace {

// What does not depend on lambda, computed once per Encode call.
struct Prepared {
  const SemiRegularMesh* mesh = nullptr;
  float quantum = 1.0f;
  std::vector<double> base_weights;
  Mesh base;                       // level-0 values to code (input numbering)
  std::vector<uint8_t> kept_bytes;
};

Status Validate(const SemiRegularMesh& mesh, const EncodeOptions& options) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  if (h.levels() < 0 || h.NumVertices(0) == 0 || h.BaseFaces().empty()) {
    return InvalidArgument("semi-regular mesh has no base faces");
  }
  if (h.levels() > bitstream::kMaxLevels) {
    return InvalidArgument("more than " + std::to_string(bitstream::kMaxLevels) + " levels");
  }
  if (mesh.positions.size() != h.NumVertices(h.levels())) {
    return InvalidArgument("semi-regular mesh has " + std::to_string(mesh.positions.size()) +
                           " positions, its hierarchy needs " +
                           std::to_string(h.NumVertices(h.levels())));
  }
  for (const Vec3& p : mesh.positions) {
    if (!p.allFinite()) return InvalidArgument("semi-regular mesh has non-finite positions");
  }
  if (!(options.lambda > 0) || !(options.tangential_factor > 0)) {
    return InvalidArgument("lambda and tangential factor must be positive");
  }
  if (options.target_bpv > 0 && options.target_psnr > 0) {
    return InvalidArgument("give a bpv target or a PSNR target, not both");
  }
  if (options.target_bpv > 0 && options.input_vertices == 0) {
    return InvalidArgument("a bpv target needs input_vertices");
  }
  if ((options.target_psnr > 0 || options.measure_psnr) && options.original == nullptr) {
    return InvalidArgument("a PSNR target or measurement needs the original mesh");
  }
  return Status::Ok();
}

StatusOr<Prepared> Prepare(const SemiRegularMesh& mesh) {
  Prepared p;
  p.mesh = &mesh;
  const double diagonal = BoundingBoxDiagonal(ExtractLevel(mesh, mesh.hierarchy.levels()));
  p.quantum = static_cast<float>(std::ldexp(diagonal > 0 ? diagonal : 1.0, -bitstream::kQuantumLog2));
  if (!(p.quantum > 0.0f) || !std::isfinite(p.quantum)) {
    return InvalidArgument("mesh extent does not fit the stream's float32 quantum");
  }
  p.base_weights = BaseInfluenceWeights(mesh.hierarchy);
  p.base.faces = mesh.hierarchy.BaseFaces();
  p.base.positions.assign(mesh.positions.begin(),
                          mesh.positions.begin() + mesh.hierarchy.NumVertices(0));
  if (!mesh.kept_exactly.faces.empty()) {
    EQMESH_ASSIGN_OR_RETURN(DracoMeshEncoding kept,
                            EncodeMeshWithDraco(mesh.kept_exactly, bitstream::kKeptBits));
    p.kept_bytes = std::move(kept.bytes);
  }
  return p;
}

// Step 3 of the loop above; appends one chunk per level.
Status EncodeLevelsUnlifted(const SemiRegularMesh& target, std::vector<Vec3> decoded,
                            const LevelCodingParams& params, const ProgressFn& progress,
                            std::vector<std::vector<uint8_t>>* chunks) {
  const SemiRegularHierarchy& h = target.hierarchy;
  for (int j = 0; j < h.levels(); ++j) {
    ReportProgress(progress, "encode level " + std::to_string(j + 1), double(j) / h.levels());
    const LevelSynthesis step(h, j, bitstream::TransformId::kUnlifted);
    const std::vector<Vec3> prediction = step.Predict(decoded);
    const std::vector<LocalFrame> frames = step.Frames(decoded);
    std::vector<Vec3> local(h.NumOddVertices(j));
    for (uint32_t k = 0; k < local.size(); ++k) {
      local[k] = ToLocalFrame(frames[k], target.positions[h.NumVertices(j) + k] - prediction[k]);
    }
    std::vector<Vec3> reconstructed;
    EQMESH_ASSIGN_OR_RETURN(std::vector<uint8_t> chunk,
                            EncodeLevelCoefficients(params, h, j, local, &reconstructed));
    chunks->push_back(std::move(chunk));
    std::vector<Vec3> fine;
    EQMESH_RETURN_IF_ERROR(step.Synthesize(decoded, frames, reconstructed, &fine));
    decoded = std::move(fine);
  }
  return Status::Ok();
}

std::vector<uint8_t> Assemble(StreamHeader header, const std::vector<uint8_t>& base,
                              const std::vector<uint8_t>& kept,
                              const std::vector<std::vector<uint8_t>>& levels,
                              EncodeReport* report) {
  header.base_size = base.size();
  header.kept_size = kept.size();
  if (!kept.empty()) header.flags |= bitstream::kHasKeptExactly;
  for (const auto& chunk : levels) header.level_sizes.push_back(chunk.size());
  std::vector<uint8_t> out = WriteStreamHeader(header);
  report->header_bytes = out.size();
  out.insert(out.end(), base.begin(), base.end());
  out.insert(out.end(), kept.begin(), kept.end());
  for (const auto& chunk : levels) {
    report->level_bytes.push_back(chunk.size());
    out.insert(out.end(), chunk.begin(), chunk.end());
  }
  report->base_bytes = base.size();
  report->kept_bytes = kept.size();
  report->total_bytes = out.size();
  return out;
}

struct Pass {
  std::vector<uint8_t> bytes;
  EncodeReport report;
};

StatusOr<Pass> EncodeAtCode(const Prepared& prep, const EncodeOptions& options, int64_t code) {
  const SemiRegularMesh& mesh = *prep.mesh;
  StreamHeader header;
  header.transform = options.transform;
  header.coder = options.coder;
  header.levels = mesh.hierarchy.levels();
  header.lambda_code = code;
  header.tangential_code = LogCode(options.tangential_factor);
  header.quantum = prep.quantum;
  const LevelCodingParams params{options.coder, header.lambda(), header.tangential_factor(),
                                 static_cast<double>(header.quantum)};
  const double lambda_world = params.lambda / (params.quantum * params.quantum);

  Pass pass;
  BaseRdReport base_report;
  EQMESH_ASSIGN_OR_RETURN(DracoMeshEncoding base,
                          EncodeBaseMesh(prep.base, prep.base_weights, lambda_world, &base_report));
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh target,
                          RenumberToBase(mesh, base.decoded_to_input, base.decoded.faces));
  std::vector<std::vector<uint8_t>> chunks;
  if (options.transform != bitstream::TransformId::kUnlifted) {
    return UnsupportedFeature("lifted transform not available in this build");
  }
  EQMESH_RETURN_IF_ERROR(
      EncodeLevelsUnlifted(target, base.decoded.positions, params, options.progress, &chunks));
  pass.bytes = Assemble(header, base.bytes, prep.kept_bytes, chunks, &pass.report);
  pass.report.lambda = params.lambda;
  pass.report.lambda_code = static_cast<int>(code);
  pass.report.base_bits = base_report.bits;
  if (options.input_vertices > 0) {
    pass.report.bpv = 8.0 * static_cast<double>(pass.bytes.size()) /
                      static_cast<double>(options.input_vertices);
  }
  return pass;
}

StatusOr<double> MeasurePsnr(const std::vector<uint8_t>& bytes, const Mesh& original) {
  EQMESH_ASSIGN_OR_RETURN(Mesh decoded, Decode(bytes.data(), bytes.size()));
#ifdef EQMESH_HAVE_METRICS
  EQMESH_ASSIGN_OR_RETURN(auto comparison, CompareSurfaces(decoded, original, {}));
  return comparison.psnr_db;
#else
  (void)original;
  return UnsupportedFeature("PSNR measurement needs eqmesh_metrics, not in this build");
#endif
}

StatusOr<Pass> EncodeWithTarget(const Prepared& prep, const EncodeOptions& options) {
  const int64_t start = LogCode(options.lambda);
  // The evaluator keeps the latest pass so the chosen point's report survives.
  std::vector<Pass> passes;
  RateEvaluator eval = [&](int64_t code) -> StatusOr<RatePoint> {
    EQMESH_ASSIGN_OR_RETURN(Pass pass, EncodeAtCode(prep, options, code));
    RatePoint point;
    point.lambda_code = code;
    point.bpv = pass.report.bpv;
    if (options.target_psnr > 0) {
      EQMESH_ASSIGN_OR_RETURN(point.psnr_db, MeasurePsnr(pass.bytes, *options.original));
      pass.report.psnr_db = point.psnr_db;
      pass.report.psnr_measured = true;
    }
    passes.push_back(std::move(pass));
    return point;
  };
  RateSearchReport search;
  RatePoint chosen;
  if (options.target_bpv > 0) {
    EQMESH_ASSIGN_OR_RETURN(chosen, SearchForRate(eval, options.target_bpv, start, 0.03, &search));
  } else {
    EQMESH_ASSIGN_OR_RETURN(chosen, SearchForQuality(eval, options.target_psnr, start, &search));
  }
  for (Pass& pass : passes) {
    if (pass.report.lambda_code == chosen.lambda_code) {
      pass.report.rate_evaluations = search.evaluations;
      return std::move(pass);
    }
  }
  return InternalError("rate control lost its chosen point");
}

}  // namespace

StatusOr<std::vector<uint8_t>> Encode(const SemiRegularMesh& mesh, const EncodeOptions& options,
                                      EncodeReport* report) {
  EQMESH_RETURN_IF_ERROR(Validate(mesh, options));
  EQMESH_ASSIGN_OR_RETURN(Prepared prep, Prepare(mesh));
  Pass pass;
  if (options.target_bpv > 0 || options.target_psnr > 0) {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeWithTarget(prep, options));
  } else {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeAtCode(prep, options, LogCode(options.lambda)));
    pass.report.rate_evaluations = 1;
  }
  if (options.measure_psnr && !pass.report.psnr_measured) {
    EQMESH_ASSIGN_OR_RETURN(pass.report.psnr_db, MeasurePsnr(pass.bytes, *options.original));
    pass.report.psnr_measured = true;
  }
  ReportProgress(options.progress, "encode", 1.0);
  if (report) *report = pass.report;
  return std::move(pass.bytes);
}

}  // namespace eqmesh

// Closed-loop encoder (see encoder.h for the papers and departures).
//
// One pass at a given lambda:
//   1. base chunk: Draco-code the level-0 values (unlifted: base positions; lifted:
//      the analysed scaling values) at the R-D chosen depth (base_mesh_encoder.h);
//   2. renumber the semi-regular mesh to the order the chunk decodes to and analyse
//      it (closed_loop.h AnalyzeAllLevels; cached while the order is unchanged);
//   3. run the closed loop of closed_loop.h from the Draco-decoded level-0 values,
//      each level coded by the header's coder (level_encoder.h);
//   4. header + chunks.
// Rate control (rate_control.h) repeats passes over lambda codes.
#include "coding/encoder.h"

#include <algorithm>

#include <cmath>
#include <cstring>
#include <deque>
#include <optional>

#include "coding/base_influence.h"
#include "coding/base_mesh_encoder.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "coding/closed_loop.h"
#include "coding/crease_chunk.h"
#include "coding/decoder.h"
#include "coding/level_encoder.h"
#include "coding/rate_control.h"
#include "coding/semi_regular_reorder.h"
#include "coding/stream_header.h"
#include "coding/stream_psnr.h"
#include "coding/zerotree/zerotree_coder.h"
#include "coding/zerotree_encoder.h"

namespace eqmesh {
namespace {

// What does not depend on lambda, computed once per Encode call.
struct Prepared {
  const SemiRegularMesh* mesh = nullptr;
  float quantum = 1.0f;
  std::vector<double> base_weights;
  // With no refinement levels the base is the decoded surface: its candidates add
  // surface-frame codings, judged by distance to the input's face planes.
  std::vector<Eigen::Matrix3d> base_quadrics;
  Mesh base;                       // level-0 values to code (input numbering)
  std::vector<MeshChunkEncoding> base_candidates;  // one per depth
  // The kept chunk: Draco, or compact (kCompactKept) in each layout, the stream's
  // layout following its base's (KeptBytes).
  std::vector<uint8_t> kept_bytes;              // Draco, or compact in the positions-after layout
  std::vector<uint8_t> kept_bytes_interleaved;  // compact only
  bool kept_compact = false;
};

// The crease chunk of a stream whose levels follow tagged base edges; empty
// when there are none (or no levels to follow them).
std::vector<uint8_t> CreaseChunkFor(const SemiRegularHierarchy& hierarchy) {
  if (hierarchy.levels() == 0 || !hierarchy.HasCreases()) return {};
  return WriteCreaseChunk(hierarchy);
}

// Step 2's result for one base order; passes at different lambdas usually share
// it, and with it what depends on the connectivity alone: the refinement steps
// and the EQ coder's level layouts (built on the first pass that needs them).
struct Renumbered {
  std::vector<uint32_t> decoded_to_input;
  std::vector<Face> faces;
  SemiRegularMesh mesh;
  AnalyzedLevels truth;
  std::vector<uint8_t> creases;  // the crease chunk (CreaseChunkFor), empty without tags
  std::optional<ClosedLoopSteps> steps;  // refers to mesh.hierarchy: set once in place
  std::vector<std::optional<EqLevelLayout>> eq_layouts;

  StatusOr<const EqLevelLayout*> EqLayout(int j) {
    std::optional<EqLevelLayout>& layout = eq_layouts[static_cast<size_t>(j)];
    if (!layout) {
      EQMESH_ASSIGN_OR_RETURN(layout, BuildEqLevelLayout(mesh.hierarchy, j));
    }
    return &*layout;
  }
};

StatusOr<Renumbered*> RenumberCached(const SemiRegularMesh& mesh, bitstream::TransformId transform,
                                     const MeshChunkEncoding& base, std::deque<Renumbered>* cache) {
  for (Renumbered& r : *cache) {
    if (r.decoded_to_input == base.decoded_to_input && r.faces == base.decoded.faces) return &r;
  }
  Renumbered r;
  r.decoded_to_input = base.decoded_to_input;
  r.faces = base.decoded.faces;
  EQMESH_ASSIGN_OR_RETURN(r.mesh, RenumberToBase(mesh, base.decoded_to_input, base.decoded.faces));
  r.truth = AnalyzeAllLevels(r.mesh.hierarchy, r.mesh.positions, transform);
  r.creases = CreaseChunkFor(r.mesh.hierarchy);
  r.eq_layouts.resize(static_cast<size_t>(r.mesh.hierarchy.levels()));
  cache->push_back(std::move(r));
  // A deque keeps its elements in place, so the steps may refer to the stored mesh.
  Renumbered& stored = cache->back();
  stored.steps.emplace(stored.mesh.hierarchy, transform);
  return &stored;
}

Status Validate(const SemiRegularMesh& mesh, const EncodeOptions& options) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  if (h.levels() < 0 || h.NumVertices(0) == 0 || h.BaseFaces().empty()) {
    if (!mesh.kept_exactly.positions.empty()) {
      return InvalidArgument("nothing was remeshed: every component is too small (" +
                             std::to_string(mesh.kept_exactly.positions.size()) +
                             " vertices in all, kept exactly); a stream needs one remeshed component");
    }
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

// Bounding-box diagonal of all positions (the semi-regular mesh has no unreferenced
// vertices, so this equals mesh.h's BoundingBoxDiagonal of the finest level).
double PositionsDiagonal(const std::vector<Vec3>& positions) {
  if (positions.empty()) return 0.0;
  Vec3 lo = positions[0], hi = positions[0];
  for (const Vec3& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

StatusOr<Prepared> Prepare(const SemiRegularMesh& mesh, bitstream::TransformId transform, bool draco_base) {
  Prepared p;
  p.mesh = &mesh;
  std::vector<Vec3> all = mesh.positions;
  all.insert(all.end(), mesh.kept_exactly.positions.begin(), mesh.kept_exactly.positions.end());
  const double diagonal = PositionsDiagonal(all);
  p.quantum = static_cast<float>(std::ldexp(diagonal > 0 ? diagonal : 1.0, -bitstream::kQuantumLog2));
  if (!(p.quantum > 0.0f) || !std::isfinite(p.quantum)) {
    return InvalidArgument("mesh extent does not fit the stream's float32 quantum");
  }
  p.base_weights = BaseInfluenceWeights(mesh.hierarchy);
  p.base.faces = mesh.hierarchy.BaseFaces();
  if (transform == bitstream::TransformId::kUnlifted) {
    p.base.positions.assign(mesh.positions.begin(),
                            mesh.positions.begin() + mesh.hierarchy.NumVertices(0));
  } else {
    p.base.positions = AnalyzeAllLevels(mesh.hierarchy, mesh.positions, transform).values[0];
  }
  const bool base_is_surface = mesh.hierarchy.levels() == 0;
  if (base_is_surface) p.base_quadrics = SurfaceErrorQuadrics(p.base);
  EQMESH_ASSIGN_OR_RETURN(p.base_candidates, EncodeBaseCandidates(p.base, draco_base, base_is_surface));
  if (!mesh.kept_exactly.faces.empty()) {
    // The compact chunk wherever it can hold the kept parts, so that a decoder built
    // without Draco reads the stream; Draco for non-manifold or inconsistently
    // oriented parts.
    auto compact = EncodeCompactBase(mesh.kept_exactly, bitstream::kKeptBits);
    if (compact.ok()) {
      p.kept_bytes = std::move(compact->bytes);
      p.kept_compact = true;
      EQMESH_ASSIGN_OR_RETURN(CompactBaseEncoding interleaved,
                              EncodeCompactBase(mesh.kept_exactly, bitstream::kKeptBits, CompactLayout::kInterleaved));
      p.kept_bytes_interleaved = std::move(interleaved.bytes);
    } else if (compact.status().code() == StatusCode::kUnsupportedFeature) {
      EQMESH_ASSIGN_OR_RETURN(MeshChunkEncoding kept,
                              EncodeMeshWithDraco(mesh.kept_exactly, bitstream::kKeptBits, false));
      p.kept_bytes = std::move(kept.bytes);
    } else {
      return compact.status().WithContext("kept-exactly components");
    }
  }
  return p;
}

// Sets the header's crease flag, size and version for `creases` (CreaseChunkFor).
void DeclareCreases(const std::vector<uint8_t>& creases, StreamHeader* header) {
  if (creases.empty()) return;
  header->flags |= bitstream::kCreaseEdges;
  header->crease_size = creases.size();
  header->version_minor = std::max(header->version_minor, bitstream::kVersionMinorCreaseEdges);
}

std::vector<uint8_t> Assemble(StreamHeader header, const std::vector<uint8_t>& base,
                              const std::vector<uint8_t>& kept, const std::vector<uint8_t>& creases,
                              const std::vector<std::vector<uint8_t>>& levels,
                              EncodeReport* report) {
  header.base_size = base.size();
  header.kept_size = kept.size();
  if (!kept.empty()) header.flags |= bitstream::kHasKeptExactly;
  DeclareCreases(creases, &header);
  for (const auto& chunk : levels) header.level_sizes.push_back(chunk.size());
  std::vector<uint8_t> out = WriteStreamHeader(header);
  report->header_bytes = out.size();
  out.insert(out.end(), base.begin(), base.end());
  out.insert(out.end(), kept.begin(), kept.end());
  out.insert(out.end(), creases.begin(), creases.end());
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
  uint64_t geometry_key = 0;  // of its decoded mesh, where a search measured it (GeometryKey)
};

StreamHeader MakeHeader(const Prepared& prep, const EncodeOptions& options, int64_t code) {
  StreamHeader header;
  header.transform = options.transform;
  header.coder = options.coder;
  header.levels = prep.mesh->hierarchy.levels();
  header.lambda_code = code;
  header.tangential_code = LogCode(options.tangential_factor);
  header.quantum = prep.quantum;
  if (options.coder == bitstream::CoderId::kEq && options.eq_tangential_context) {
    header.flags |= bitstream::kTangentialContext;
  }
  if (prep.kept_compact) {
    header.flags |= bitstream::kCompactKept;
    header.version_minor = bitstream::kVersionMinorCompactKept;
  }
  return header;
}

// The layout of the stream's compact chunks: the base's where it is compact, else
// the kept chunk's smaller one.
CompactLayout StreamLayout(const Prepared& prep, const MeshChunkEncoding& base) {
  if (base.compact) return base.layout;
  return prep.kept_compact && prep.kept_bytes_interleaved.size() <= prep.kept_bytes.size()
             ? CompactLayout::kInterleaved
             : CompactLayout::kPositionsAfter;
}

const std::vector<uint8_t>& KeptBytes(const Prepared& prep, const MeshChunkEncoding& base) {
  return prep.kept_compact && StreamLayout(prep, base) == CompactLayout::kInterleaved ? prep.kept_bytes_interleaved
                                                                                       : prep.kept_bytes;
}

// The base candidate of least R + lambda D at the header's lambda.
const MeshChunkEncoding& ChooseBase(const Prepared& prep, const StreamHeader& header, BaseRdReport* report) {
  const double quantum = static_cast<double>(header.quantum);
  const double lambda_world = header.lambda() / (quantum * quantum);
  return prep.base_candidates[ChooseBaseCandidate(prep.base_candidates, prep.base, prep.base_weights,
                                                  lambda_world, report,
                                                  prep.base_quadrics.empty() ? nullptr : &prep.base_quadrics)];
}

Pass FinishPass(StreamHeader header, const Prepared& prep, const MeshChunkEncoding& base,
                const std::vector<uint8_t>& creases, const std::vector<std::vector<uint8_t>>& chunks,
                const BaseRdReport& base_report, const EncodeOptions& options) {
  Pass pass;
  if (base.compact) header.flags |= bitstream::kCompactBase;
  if ((base.compact || prep.kept_compact) && StreamLayout(prep, base) == CompactLayout::kPositionsAfter) {
    header.flags |= bitstream::kCompactPositionsAfter;
    header.version_minor = std::max(header.version_minor, bitstream::kVersionMinorPositionsAfter);
  }
  if (base.compact && base.parallelogram_choice) {
    header.flags |= bitstream::kParallelogramChoice;
    header.version_minor = std::max(header.version_minor, bitstream::kVersionMinorParallelogramChoice);
  }
  pass.bytes = Assemble(header, base.bytes, KeptBytes(prep, base), creases, chunks, &pass.report);
  pass.report.lambda = header.lambda();
  pass.report.tangential_factor = header.tangential_factor();
  pass.report.lambda_code = static_cast<int>(header.lambda_code);
  pass.report.base_bits = base_report.depth;
  pass.report.base_compact = base.compact;
  pass.report.base_tangential_step = base.tangential_quarters / 4.0;
  if (options.input_vertices > 0) {
    pass.report.bpv = 8.0 * static_cast<double>(pass.bytes.size()) /
                      static_cast<double>(options.input_vertices);
  }
  return pass;
}

StatusOr<Pass> EncodeAtCode(const Prepared& prep, const EncodeOptions& options, int64_t code,
                            std::deque<Renumbered>* cache) {
  const StreamHeader header = MakeHeader(prep, options, code);
  const LevelCodingParams params{options.coder,
                                 code,
                                 header.lambda(),
                                 header.tangential_factor(),
                                 static_cast<double>(header.quantum),
                                 header.has_tangential_context()};
  BaseRdReport base_report;
  const MeshChunkEncoding& base = ChooseBase(prep, header, &base_report);
  EQMESH_ASSIGN_OR_RETURN(Renumbered* const target, RenumberCached(*prep.mesh, options.transform, base, cache));
  const SemiRegularHierarchy& h = target->mesh.hierarchy;
  const LevelCoderFn coder = [&](int j, const std::vector<Vec3>& local,
                                 std::vector<Vec3>* reconstructed) -> StatusOr<std::vector<uint8_t>> {
    const EqLevelLayout* layout = nullptr;
    if (params.coder == bitstream::CoderId::kEq) {
      EQMESH_ASSIGN_OR_RETURN(layout, target->EqLayout(j));
    }
    return EncodeLevelCoefficients(params, h, j, local, reconstructed, layout);
  };
  std::vector<std::vector<uint8_t>> chunks;
  EQMESH_RETURN_IF_ERROR(
      EncodeLevelsClosedLoop(*target->steps, target->truth, base.decoded.positions, coder, options.progress, &chunks)
          .status());
  return FinishPass(header, prep, base, target->creases, chunks, base_report, options);
}

// Zerotree payload bytes that keep the whole stream within total_budget (never
// below the smallest payload: a budget under the base chunk gives the smallest
// stream there is).
uint64_t ZerotreePayloadBudget(StreamHeader header, size_t base_bytes, size_t kept_bytes,
                               const std::vector<uint8_t>& creases, uint64_t total_budget) {
  header.base_size = base_bytes;
  header.kept_size = kept_bytes;
  if (kept_bytes > 0) header.flags |= bitstream::kHasKeptExactly;
  DeclareCreases(creases, &header);
  header.level_sizes.assign(static_cast<size_t>(header.levels), 0);
  header.level_sizes[0] = total_budget;  // an upper bound on the real size's varint
  const uint64_t fixed = WriteStreamHeader(header).size() + base_bytes + kept_bytes + creases.size();
  const uint64_t least = ZerotreeMinBytes();
  return total_budget > fixed + least ? total_budget - fixed : least;
}

// One zerotree pass (zerotree_encoder.h): lambda (the code) chooses the base and,
// without a budget (total_budget 0), the last bit plane; *last_plane receives the
// plane the payload ended in.
StatusOr<Pass> EncodeZerotreeAtCode(const Prepared& prep, const EncodeOptions& options, int64_t code,
                                    uint64_t total_budget, std::deque<Renumbered>* cache,
                                    int* last_plane) {
  const StreamHeader header = MakeHeader(prep, options, code);
  BaseRdReport base_report;
  const MeshChunkEncoding& base = ChooseBase(prep, header, &base_report);
  EQMESH_ASSIGN_OR_RETURN(const Renumbered* target, RenumberCached(*prep.mesh, options.transform, base, cache));
  const SemiRegularHierarchy& h = target->mesh.hierarchy;
  std::vector<std::vector<uint8_t>> chunks(static_cast<size_t>(h.levels()));
  *last_plane = 0;
  if (h.levels() > 0) {
    ReportProgress(options.progress, "encode zerotree", 0.0);
    EQMESH_ASSIGN_OR_RETURN(const auto coeffs, ZerotreeCoefficients(*target->steps, target->truth,
                                                                    base.decoded.positions));
    ZerotreeOptions zo;
    zo.quantum = static_cast<double>(header.quantum);
    zo.tangential_factor = header.tangential_factor();
    if (total_budget > 0) {
      zo.byte_budget = ZerotreePayloadBudget(header, base.bytes.size(), KeptBytes(prep, base).size(),
                                             target->creases, total_budget);
    } else {
      zo.min_plane = ZerotreePlaneForLambda(header.lambda());
    }
    ZerotreeEncodeReport zr;
    EQMESH_ASSIGN_OR_RETURN(chunks[0], EncodeZerotree(h, coeffs, zo, &zr));
    *last_plane = zr.last_plane;
  }
  return FinishPass(header, prep, base, target->creases, chunks, base_report, options);
}

// A byte budget cut exactly (embedded stream): a first pass at the start lambda
// finds the plane the budget reaches; if that plane's lambda chooses another
// base, the second pass codes with it (equal R-D slopes for base and details).
StatusOr<Pass> EncodeZerotreeToBudget(const Prepared& prep, const EncodeOptions& options, uint64_t total_budget,
                                      std::deque<Renumbered>* cache) {
  int plane = 0;
  const int64_t start = LogCode(options.lambda);
  EQMESH_ASSIGN_OR_RETURN(Pass first, EncodeZerotreeAtCode(prep, options, start, total_budget, cache, &plane));
  first.report.rate_evaluations = 1;
  const int64_t code = LogCode(ZerotreeLambdaForPlane(plane));
  BaseRdReport at_start, at_plane;
  const StreamHeader start_header = MakeHeader(prep, options, start);
  const StreamHeader plane_header = MakeHeader(prep, options, code);
  if (&ChooseBase(prep, start_header, &at_start) == &ChooseBase(prep, plane_header, &at_plane)) return first;
  EQMESH_ASSIGN_OR_RETURN(Pass second, EncodeZerotreeAtCode(prep, options, code, total_budget, cache, &plane));
  second.report.rate_evaluations = 2;
  return second;
}

// A PSNR-target search measures every trial stream. At the meter's default
// (1M samples per direction) that would dominate the encode time; 200k samples
// spread about 0.012 dB between seeds (surface_distance.cpp), so the search
// aims kSearchMarginDb above the target at a fifth of the cost, and only the
// chosen stream is measured at the default count (FinishQualitySearch).
constexpr uint64_t kSearchSamples = 200'000;
constexpr double kSearchMarginDb = 0.05;

// Whether `pass` (searched for a PSNR target) shows that no stream meeting the
// target is smaller than options.outbid_bytes: it misses the search's aim with
// at least that many bytes.
bool Outbid(const EncodeOptions& options, const Pass& pass) {
  return options.outbid_bytes > 0 && pass.report.psnr_db < options.target_psnr + kSearchMarginDb &&
         pass.bytes.size() >= options.outbid_bytes;
}

// The search's choice, measured at the default sample count; in the rare case
// that it then misses the target, the smallest other pass that meets it (none:
// the best one tried). Without options.verify_target, the choice as searched.
StatusOr<Pass> FinishQualitySearch(std::vector<Pass> passes, size_t chosen, const EncodeOptions& options,
                                   int evaluations) {
  if (chosen >= passes.size()) return InternalError("rate control lost its chosen point");
  if (!options.verify_target) {
    passes[chosen].report.psnr_measured = true;
    passes[chosen].report.rate_evaluations = evaluations;
    return std::move(passes[chosen]);
  }
  std::swap(passes[0], passes[chosen]);
  std::sort(passes.begin() + 1, passes.end(), [](const Pass& a, const Pass& b) {
    return a.bytes.size() != b.bytes.size() ? a.bytes.size() < b.bytes.size()
                                            : a.report.psnr_db > b.report.psnr_db;
  });
  Pass* best = nullptr;
  for (Pass& pass : passes) {
    if (&pass != &passes[0] && pass.report.psnr_db < options.target_psnr + kSearchMarginDb) continue;
    EQMESH_ASSIGN_OR_RETURN(pass.report.psnr_db, MeasureEncodedPsnr(pass.bytes, options, 0));
    if (pass.report.psnr_db >= options.target_psnr) {
      best = &pass;
      break;
    }
  }
  if (best == nullptr) best = &passes[0];
  best->report.psnr_measured = true;
  best->report.rate_evaluations = evaluations;
  return std::move(*best);
}

uint64_t BudgetForBpv(double bpv, size_t input_vertices) {
  return static_cast<uint64_t>(std::floor(bpv * static_cast<double>(input_vertices) / 8.0));
}

// PSNR target for the embedded coder: search the byte budget, not lambda.
StatusOr<Pass> EncodeZerotreeForQuality(const Prepared& prep, const EncodeOptions& options,
                                        std::deque<Renumbered>* cache) {
  std::vector<Pass> passes;
  BudgetEvaluator eval = [&](uint64_t budget) -> StatusOr<BudgetPoint> {
    EQMESH_ASSIGN_OR_RETURN(Pass pass, EncodeZerotreeToBudget(prep, options, budget, cache));
    EQMESH_ASSIGN_OR_RETURN(pass.report.psnr_db, MeasureEncodedPsnr(pass.bytes, options, kSearchSamples));
    const BudgetPoint point{budget, pass.bytes.size(), pass.report.psnr_db};
    passes.push_back(std::move(pass));
    return point;
  };
  // Start from the stream the start lambda's bit plane gives.
  int plane = 0;
  EQMESH_ASSIGN_OR_RETURN(const Pass first, EncodeZerotreeAtCode(prep, options, LogCode(options.lambda), 0,
                                                                 cache, &plane));
  RateSearchReport search;
  EQMESH_ASSIGN_OR_RETURN(const BudgetPoint chosen,
                          SearchBudgetForQuality(eval, options.target_psnr + kSearchMarginDb, first.bytes.size(), 1,
                                                 &search));
  size_t index = 0;
  while (index + 1 < passes.size() &&
         !(passes[index].bytes.size() == chosen.size && passes[index].report.psnr_db == chosen.psnr_db)) {
    ++index;
  }
  return FinishQualitySearch(std::move(passes), index, options, search.evaluations + 1);
}

bool WithinRate(double bpv, double target) { return std::abs(bpv - target) <= kBpvTolerance * target; }

// The EQ stream's size can jump between adjacent lambda codes (bunny, 6 levels,
// 4 bpv: 3.86 -> 4.34 bpv, when most finest-level coefficients leave the dead
// zone together), so no lambda meets the target. The tangential factor is the
// stream's second rate knob and moves only the tangential bits: at the lambda
// code of the pass nearest the target, search it for the rate (tangential code
// = start - u, so the size grows with u as SearchForRate expects). Returns the
// pass it ends on (nullopt when the search found nothing nearer).
StatusOr<std::optional<Pass>> MatchRateWithTangential(const Prepared& prep, const EncodeOptions& options,
                                                      std::deque<Renumbered>* cache, const Pass& nearest,
                                                      int* evaluations) {
  const int64_t lambda_code = nearest.report.lambda_code;
  const int64_t start = LogCode(options.tangential_factor);
  std::vector<Pass> passes;
  std::vector<int64_t> pass_u;
  RateEvaluator eval = [&](int64_t u) -> StatusOr<RatePoint> {
    Pass pass;
    if (u == 0) {
      pass = nearest;  // the search starts at the pass it refines: no need to code it again
    } else {
      EncodeOptions o = options;
      o.tangential_factor = FromLogCode(std::clamp(start - u, -bitstream::kMaxLogCode, bitstream::kMaxLogCode));
      EQMESH_ASSIGN_OR_RETURN(pass, EncodeAtCode(prep, o, lambda_code, cache));
    }
    RatePoint point;
    point.lambda_code = u;
    point.bpv = pass.report.bpv;
    passes.push_back(std::move(pass));
    pass_u.push_back(u);
    return point;
  };
  RateSearchReport search;
  EQMESH_ASSIGN_OR_RETURN(const RatePoint chosen, SearchForRate(eval, options.target_bpv, 0, kBpvTolerance, &search));
  *evaluations += search.evaluations - 1;  // the first, u = 0, was `nearest`
  if (std::abs(chosen.bpv - options.target_bpv) >= std::abs(nearest.report.bpv - options.target_bpv)) {
    return std::optional<Pass>();
  }
  for (size_t i = 0; i < passes.size(); ++i) {
    if (pass_u[i] == chosen.lambda_code) return std::optional<Pass>(std::move(passes[i]));
  }
  return InternalError("rate control lost its chosen tangential point");
}

// A hash of a mesh's position bits and faces (FNV-1a's step over 64-bit words):
// a cheap first test of whether two trial streams decode to the same geometry.
uint64_t GeometryKey(const Mesh& mesh) {
  uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](uint64_t word) { h = (h ^ word) * 1099511628211ull; };
  for (const Vec3& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      uint64_t bits;
      std::memcpy(&bits, &p[k], sizeof(bits));
      mix(bits);
    }
  }
  for (const Face& f : mesh.faces) mix((uint64_t{f[0]} << 32 | f[1]) ^ (uint64_t{f[2]} << 16));
  return h;
}

// A search pass's PSNR as MeasureEncodedPsnr takes it (*key: its geometry's
// GeometryKey), or an earlier pass's where that one decodes to the same mesh:
// lambda codes a few steps apart often give the same geometry (an as-is
// stream changes only where its grid depth does; lambda steers level chunks
// alone), and the meter is most of a search's time (10 of the 71 measurements
// of a cow --psnr 70 encode were of a geometry it had measured before).
StatusOr<double> MeasureSearchPass(const Pass& pass, const std::vector<Pass>& earlier, const EncodeOptions& options,
                                   uint64_t* key) {
  EQMESH_ASSIGN_OR_RETURN(const Mesh decoded, DecodeForMeasure(pass.bytes, options.max_triangles));
  *key = GeometryKey(decoded);
  for (const Pass& other : earlier) {
    if (other.geometry_key != *key) continue;
    EQMESH_ASSIGN_OR_RETURN(const Mesh again, DecodeForMeasure(other.bytes, options.max_triangles));
    if (again.positions == decoded.positions && again.faces == decoded.faces) return other.report.psnr_db;
  }
  return MeasureMeshPsnr(decoded, *options.original, MeasureSamples(options, kSearchSamples),
                         options.prepared_original.get());
}

// A lambda-code evaluator that keeps every pass (so the chosen point's report
// survives), measuring each one's PSNR when asked to.
RateEvaluator RecordingEvaluator(const Prepared& prep, const EncodeOptions& options, std::deque<Renumbered>* cache,
                                 bool measure, std::vector<Pass>* passes) {
  return [&prep, &options, cache, measure, passes](int64_t code) -> StatusOr<RatePoint> {
    EQMESH_ASSIGN_OR_RETURN(Pass pass, EncodeAtCode(prep, options, code, cache));
    RatePoint point;
    point.lambda_code = code;
    point.bpv = pass.report.bpv;
    if (measure) {
      EQMESH_ASSIGN_OR_RETURN(point.psnr_db, MeasureSearchPass(pass, *passes, options, &pass.geometry_key));
      pass.report.psnr_db = point.psnr_db;
      if (Outbid(options, pass)) return Status(StatusCode::kOutbid, "a stream of this mesh meeting the target is larger");
    }
    passes->push_back(std::move(pass));
    return point;
  };
}

// The pass nearest the target on the other side of it from `nearest` (null when
// every pass lies on one side).
const Pass* NearestAcross(const std::vector<Pass>& passes, const Pass& nearest, double target) {
  const Pass* across = nullptr;
  for (const Pass& pass : passes) {
    const bool other_side = (pass.report.bpv < target) != (nearest.report.bpv < target);
    if (other_side && (!across || std::abs(pass.report.bpv - target) < std::abs(across->report.bpv - target))) {
      across = &pass;
    }
  }
  return across;
}

StatusOr<Pass> EncodeForRate(const Prepared& prep, const EncodeOptions& options, std::deque<Renumbered>* cache) {
  std::vector<Pass> passes;
  const RateEvaluator eval = RecordingEvaluator(prep, options, cache, false, &passes);
  RateSearchReport search;
  const double target = options.target_bpv;
  EQMESH_ASSIGN_OR_RETURN(const RatePoint chosen,
                          SearchForRate(eval, target, LogCode(options.lambda), kBpvTolerance, &search));
  const Pass* nearest = nullptr;
  for (const Pass& pass : passes) {
    if (pass.report.lambda_code == chosen.lambda_code) nearest = &pass;
  }
  if (nearest == nullptr) return InternalError("rate control lost its chosen point");
  const Pass* across = NearestAcross(passes, *nearest, target);
  Pass result = *nearest;
  // Only a jump across the target is closed this way: with every pass on one
  // side the target is out of this level count's reach (the level search's
  // coarse candidates at high rates), and the tangential factor would not help.
  if (across == nullptr) {
    result.report.rate_evaluations = search.evaluations;
    return result;
  }
  for (const Pass* start : {nearest, across}) {
    if (WithinRate(result.report.bpv, target)) break;
    EQMESH_ASSIGN_OR_RETURN(std::optional<Pass> refined,
                            MatchRateWithTangential(prep, options, cache, *start, &search.evaluations));
    if (refined && std::abs(refined->report.bpv - target) < std::abs(result.report.bpv - target)) {
      result = std::move(*refined);
    }
  }
  result.report.rate_evaluations = search.evaluations;
  return result;
}

StatusOr<Pass> EncodeWithTarget(const Prepared& prep, const EncodeOptions& options,
                                std::deque<Renumbered>* cache) {
  if (options.target_bpv > 0) return EncodeForRate(prep, options, cache);
  const int64_t start = LogCode(options.lambda);
  std::vector<Pass> passes;
  const RateEvaluator eval = RecordingEvaluator(prep, options, cache, true, &passes);
  RateSearchReport search;
  EQMESH_ASSIGN_OR_RETURN(const RatePoint chosen,
                          SearchForQuality(eval, options.target_psnr + kSearchMarginDb, start, &search));
  size_t index = 0;
  while (index + 1 < passes.size() && passes[index].report.lambda_code != chosen.lambda_code) ++index;
  return FinishQualitySearch(std::move(passes), index, options, search.evaluations);
}

}  // namespace

double DefaultTangentialFactor(bitstream::TransformId transform) {
  return transform == bitstream::TransformId::kLifted ? 4.0 : 2.0;
}

EncodeOptions WithPreparedOriginal(const EncodeOptions& options) {
  const bool measures = options.target_psnr > 0 || options.target_bpv > 0 || options.measure_psnr;
  if (!measures || options.original == nullptr ||
      (options.prepared_original != nullptr && options.prepared_original->mesh == options.original)) {
    return options;
  }
  EncodeOptions out = options;
  // An original the meter refuses (or a build without it) is left to each
  // measurement, which reports why where the measurement is needed.
  auto prepared = PrepareOriginal(*options.original);
  out.prepared_original = prepared.ok() ? *std::move(prepared) : nullptr;
  return out;
}

StatusOr<double> MeasureEncodedPsnr(const std::vector<uint8_t>& stream, const EncodeOptions& options,
                                    uint64_t fallback) {
  return MeasureStreamPsnr(stream, *options.original, MeasureSamples(options, fallback), options.max_triangles,
                           options.prepared_original.get());
}

StatusOr<std::vector<uint8_t>> Encode(const SemiRegularMesh& mesh, const EncodeOptions& requested,
                                      EncodeReport* report) {
  EncodeOptions options = requested;
  if (options.tangential_factor == 0) options.tangential_factor = DefaultTangentialFactor(options.transform);
  EQMESH_RETURN_IF_ERROR(Validate(mesh, options));
  options = WithPreparedOriginal(options);
  EQMESH_ASSIGN_OR_RETURN(Prepared prep, Prepare(mesh, options.transform, options.draco_base));
  std::deque<Renumbered> cache;
  Pass pass;
  const bool zerotree = options.coder == bitstream::CoderId::kZerotree;
  if (zerotree && options.target_bpv > 0) {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeZerotreeToBudget(
                                      prep, options, BudgetForBpv(options.target_bpv, options.input_vertices), &cache));
  } else if (zerotree && options.target_psnr > 0) {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeZerotreeForQuality(prep, options, &cache));
  } else if (zerotree) {
    int plane = 0;
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeZerotreeAtCode(prep, options, LogCode(options.lambda), 0, &cache, &plane));
    pass.report.rate_evaluations = 1;
  } else if (options.target_bpv > 0 || options.target_psnr > 0) {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeWithTarget(prep, options, &cache));
  } else {
    EQMESH_ASSIGN_OR_RETURN(pass, EncodeAtCode(prep, options, LogCode(options.lambda), &cache));
    pass.report.rate_evaluations = 1;
  }
  if (options.measure_psnr && !pass.report.psnr_measured) {
    EQMESH_ASSIGN_OR_RETURN(pass.report.psnr_db, MeasureEncodedPsnr(pass.bytes, options, 0));
    pass.report.psnr_measured = true;
  }
  ReportProgress(options.progress, "encode", 1.0);
  if (report) *report = pass.report;
  return std::move(pass.bytes);
}

}  // namespace eqmesh

// Remesh(): input checks, component split, MAPS base domain, then normal-mesh
// piercing level by level (Lee et al. 1998; Guskov et al. 2000). See remesh.h.
#include "remesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "mesh/mesh_topology.h"
#include "mesh/repair.h"
#include "mesh/triangle_bvh.h"
#include "metrics/surface_distance.h"
#include "remesh/base_domain.h"
#include "remesh/input_check.h"
#include "remesh/quality_checks.h"
#include "remesh/piercing.h"
#include "remesh/untangle.h"

namespace eqmesh {
namespace {

// Automatic levels refine until the finest level has at least this many times
// the input's vertices (dense scans: no input vertex's detail falls between
// remesh vertices) ...
constexpr double kAutoMinVertexFactor = 8.0;
// ... and its mean edge is at most this share of the bounding-box diagonal. The
// PSNR is relative to the diagonal, and on faceted inputs (2k-30k vertices) the
// remesh error is set by how finely it crosses the input's creases, whatever
// the input's vertex count: 80 dB needs about this resolution there.
constexpr double kAutoMaxEdgeShare = 1.0 / 500.0;
// Past that, a level is added only while the last one measures below this
// PSNR against the input (Metro, kLevelPsnrSamples samples each way) and gains
// at least kAutoMinGainDb over the one before: faceted inputs need more than
// the density rule, dense scans rarely do ...
constexpr double kAutoTargetPsnrDb = 86.0;
constexpr double kAutoMinGainDb = 0.5;
constexpr uint64_t kLevelPsnrSamples = 100'000;
// ... and only when the added level stays below this many vertices: measuring a
// level costs a search tree over it, a fifth of a dense scan's remesh time.
constexpr uint64_t kAutoMaxMeasuredVertices = 1'000'000;
// Refinement stops before the finest level would exceed this multiple of the
// input vertices ...
constexpr double kAutoMaxVertexFactor = 128.0;
// ... or this many vertices at all: the codec's level search never keeps such
// levels below 4 bpv, and memory grows ~400 bytes per remesh vertex.
constexpr uint64_t kAutoMaxVertices = 3'000'000;
constexpr int kMaxLevels = 10;
// Components with fewer vertices are carried as they are (kept_exactly).
constexpr size_t kMinComponentVertices = 20;
// Automatic base: the simplification stops where an input vertex would end up
// farther than this share of its component's diagonal from the base
// (base_domain.h) ...
constexpr double kBaseErrorShare = 0.02;
// ... or once this fraction of the input vertices is left, whichever comes
// first (but never below kMinBasePerComponent per remeshed component). On dense
// scans the bound is loose, and bases of this size remesh them best (measured:
// bench/log/2026-12-05-base-bound-and-levels.md).
constexpr double kMinBaseFraction = 0.003;
constexpr size_t kMinBasePerComponent = 8;
// RemeshOptions::min_psnr: how many times the base bound is halved to meet it,
// and how far below it a remesh may measure for that to be tried. Four halvings
// (2 % down to 0.125 %) and 20 dB: man measures 69.5 dB at 2 % and 81.8 dB at
// 1 %; femur (genus 2) needs 0.25 %, and its PSNR is not monotone in the bound
// (77.5, 78.4, 74.1, 83.4 dB), so every halving is measured and the best kept.
constexpr int kFloorRetries = 4;
constexpr double kFloorReachDb = 20.0;
// A remesh measured (kLevelPsnrSamples) less than this above the floor is
// measured again with kFloorConfirmSamples before the floor counts as met:
// where the error gathers in a few small regions 100k samples can read high (a
// dragon_vrip remesh with one spike: 81.97 dB at 100k, 81.27 at 1M, 81.31 at
// 4.4M), and `eqmesh remesh` reports the meter's default.
constexpr double kFloorConfirmDb = 1.0;
constexpr uint64_t kFloorConfirmSamples = 1'000'000;
// Remeshes with the base bound tightened where the finest level still folds
// (RemeshWithFewerFolds), and the factor each applies there.
constexpr int kFoldRetries = 2;
constexpr double kFoldBoundScale = 0.25;
// Where the automatic level count's remesh still folds after those retries,
// remeshes with up to this many levels fewer (RemeshWithFewerLevels), on inputs
// of up to kFoldLevelDropVertices vertices: each drop is a whole remesh with
// its floor and fold retries, which on a large scan costs minutes (a remesh of
// dragon_vrip, 437k vertices, takes 130 s) for a level count its density seldom
// allows.
constexpr int kFoldLevelDrops = 2;
constexpr size_t kFoldLevelDropVertices = 60'000;

struct Prepared {
  Mesh surface;                  // components to remesh, compacted
  std::vector<uint8_t> boundary; // per surface vertex
  Mesh kept;                     // components carried exactly
  size_t components_remeshed = 0;
  size_t components_kept = 0;
  size_t boundary_loops = 0;
  size_t input_vertices = 0;
};

Mesh DropRepeatedIndexFaces(const Mesh& in, size_t* dropped) {
  Mesh out;
  out.positions = in.positions;
  for (const Face& f : in.faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      ++*dropped;
      continue;
    }
    out.faces.push_back(f);
  }
  return out;
}

// Copies the faces selected by `take` into a compact mesh.
Mesh ExtractFaces(const Mesh& m, const std::vector<uint8_t>& take, std::vector<uint32_t>* vmap_out) {
  Mesh out;
  std::vector<uint32_t> vmap(m.positions.size(), MeshTopology::kNone);
  for (size_t f = 0; f < m.faces.size(); ++f) {
    if (!take[f]) continue;
    Face nf;
    for (int i = 0; i < 3; ++i) {
      uint32_t& slot = vmap[m.faces[f][i]];
      if (slot == MeshTopology::kNone) {
        slot = static_cast<uint32_t>(out.positions.size());
        out.positions.push_back(m.positions[m.faces[f][i]]);
      }
      nf[i] = slot;
    }
    out.faces.push_back(nf);
  }
  if (vmap_out) *vmap_out = std::move(vmap);
  return out;
}

StatusOr<Prepared> Prepare(const Mesh& input, const RemeshOptions& options, RemeshReport* report) {
  Mesh mesh;
  if (options.repair) {
    RepairReport repair;
    EQMESH_ASSIGN_OR_RETURN(mesh, RepairForRemeshing(input, &repair));
    if (!repair.Unchanged()) report->notes.push_back("repair: " + repair.Summary());
    report->welded_vertices = repair.vertices_welded;
  } else {
    // The surface, not the file's vertex numbering, is what gets remeshed: split
    // seams would cut it into patches remeshed apart (a triangle soup into
    // components too small to remesh at all).
    mesh = WeldSeams(input, &report->welded_vertices);
    if (report->welded_vertices > 0) {
      report->notes.push_back("welded " + std::to_string(report->welded_vertices) +
                              " vertices sharing a position with another (split seams)");
    }
  }
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces");
  {
    const MeshTopology topology(mesh);
    EQMESH_RETURN_IF_ERROR(CheckRemeshable(mesh, topology));
  }
  size_t dropped = 0;
  mesh = DropRepeatedIndexFaces(mesh, &dropped);
  if (dropped > 0) report->notes.push_back("dropped " + std::to_string(dropped) + " faces with a repeated vertex");
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces with three distinct vertices");
  mesh = ExtractFaces(mesh, std::vector<uint8_t>(mesh.faces.size(), 1), nullptr);

  Prepared out;
  out.input_vertices = mesh.positions.size();
  const MeshTopology topology(mesh);
  const std::vector<uint32_t>& comp = topology.FaceComponents();
  std::vector<size_t> comp_vertices(topology.num_components(), 0);
  std::vector<uint32_t> vertex_comp(mesh.positions.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t v : mesh.faces[f]) vertex_comp[v] = comp[f];
  }
  for (uint32_t c : vertex_comp) ++comp_vertices[c];
  std::vector<uint8_t> remesh_face(mesh.faces.size(), 0), kept_face(mesh.faces.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const bool small = comp_vertices[comp[f]] < kMinComponentVertices;
    (small ? kept_face : remesh_face)[f] = 1;
  }
  for (size_t n : comp_vertices) (n < kMinComponentVertices ? out.components_kept : out.components_remeshed)++;
  std::vector<uint32_t> vmap;
  out.surface = ExtractFaces(mesh, remesh_face, &vmap);
  out.kept = ExtractFaces(mesh, kept_face, nullptr);
  out.boundary.assign(out.surface.positions.size(), 0);
  const std::vector<BoundaryLoop> loops = topology.BoundaryLoops();
  for (const BoundaryLoop& loop : loops) {
    bool remeshed = false;
    for (uint32_t v : loop.vertices) {
      if (vmap[v] != MeshTopology::kNone) {
        out.boundary[vmap[v]] = 1;
        remeshed = true;
      }
    }
    if (remeshed) ++out.boundary_loops;
  }
  return out;
}

BaseDomainOptions BaseOptions(const Prepared& p, const RemeshOptions& options, double error_share) {
  BaseDomainOptions base;
  base.progress = options.progress;
  base.raise_valence_three = options.levels != 0;
  if (options.base_vertices > 0) {
    base.target_vertices = static_cast<size_t>(options.base_vertices);
    return base;
  }
  const size_t by_fraction = static_cast<size_t>(kMinBaseFraction * static_cast<double>(p.input_vertices));
  base.target_vertices = std::max(by_fraction, kMinBasePerComponent * p.components_remeshed);
  base.max_error_share = error_share;
  return base;
}

double EstimatedPsnrDb(double diagonal, double rms) {
  if (!(rms > 0.0)) return 200.0;
  return 20.0 * std::log10(diagonal / rms);
}

// What the automatic level count aims for (kAutoMinVertexFactor, kAutoMaxEdgeShare).
struct DensityTarget {
  uint64_t input_vertices = 0;
  // Faces whose mean edge over the input's area is kAutoMaxEdgeShare of the
  // diagonal: an equilateral triangle of edge e has area sqrt(3)/4 e^2.
  double faces = 0.0;
};

DensityTarget AutoDensityTarget(const Mesh& surface, size_t input_vertices) {
  double area = 0.0;
  for (const Face& f : surface.faces) {
    area += 0.5 * (surface.positions[f[1]] - surface.positions[f[0]])
                      .cross(surface.positions[f[2]] - surface.positions[f[0]])
                      .norm();
  }
  const double edge = kAutoMaxEdgeShare * BoundingBoxDiagonal(surface);
  return {input_vertices, edge > 0.0 ? 4.0 * area / (std::sqrt(3.0) * edge * edge) : 0.0};
}

struct LevelSize {
  uint64_t vertices = 0, faces = 0;
};

enum class LevelDecision { kStop, kRefine, kMeasureFirst };

// Whether to add a level after `levels_done` (see the constants at the top).
LevelDecision NextLevel(const RemeshOptions& options, int levels_done, LevelSize current, LevelSize next,
                        const DensityTarget& target) {
  if (options.levels >= 0) return levels_done >= options.levels ? LevelDecision::kStop : LevelDecision::kRefine;
  if (levels_done >= kMaxLevels) return LevelDecision::kStop;
  const double input = static_cast<double>(target.input_vertices);
  if (static_cast<double>(next.vertices) > kAutoMaxVertexFactor * input) return LevelDecision::kStop;
  if (next.vertices > kAutoMaxVertices) return LevelDecision::kStop;
  const bool dense = levels_done > 0 && static_cast<double>(current.vertices) >= kAutoMinVertexFactor * input &&
                     static_cast<double>(current.faces) >= target.faces;
  if (!dense) return LevelDecision::kRefine;
  return next.vertices > kAutoMaxMeasuredVertices ? LevelDecision::kStop : LevelDecision::kMeasureFirst;
}

// Metro PSNR of the level against the surface it remeshes (a sampled estimate:
// `samples` per direction).
double MeasureLevelPsnr(const ReferenceSurface& surface, const std::vector<Vec3>& positions,
                        const std::vector<Face>& faces, uint64_t samples = kLevelPsnrSamples) {
  Mesh level;
  level.positions = positions;
  level.faces = faces;
  CompareOptions compare;
  compare.samples = samples;
  const StatusOr<SurfaceDistance> d = surface.Compare(level, compare);
  return d.ok() ? d->psnr_db : 0.0;
}

// One complete refinement of the base domain.
struct Refinement {
  SemiRegularHierarchy hierarchy;
  std::vector<Vec3> positions;
  std::vector<uint32_t> on_faces;  // input triangle under each position (piercing.h)
  std::vector<VertexKind> kinds;
  std::vector<CreasePlace> creases;  // where each position lies on the input's crease chains
  int levels = 0;
  std::vector<double> estimated_psnr_db_per_level;
  std::vector<StencilTable> stencils;  // of each refinement, for the untangling
  std::vector<uint32_t> folded_faces;  // of the finest level, as far as known
  std::vector<uint32_t> input_base_face;  // base face of each input vertex's parameter
  RemeshParts parts;                      // of the base faces
  double untangle_seconds = 0.0;
};

// Unfolds the level just pierced before the next is pierced from it, so a fold
// is mended where it first appears, over a few faces, instead of at the finest
// level, where subdividing a folded face has folded all its descendants (man:
// 2,821 finest folds, 2,319 of them descendants of coarser folds), as a level
// pierced from (LevelUse); UntangleFinalFolds takes what still folds once the
// last level is pierced. Only where the next level is refined in 3D
// (RefinedIn3d): a chart-refined level places its vertices by the input's
// parameters, which a moved vertex no longer matches (horse: 0.5 dB lost).
// A moved vertex's input triangle is no longer known.
void UntangleNewLevel(const InputSurface& surface, const std::vector<uint32_t>& folded, Refinement* r) {
  r->folded_faces = folded;
  if (folded.empty() || !RefinedIn3d(r->hierarchy.Faces(r->levels).size(), surface.mesh->faces.size())) return;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Vec3> before = r->positions;
  UntangleFinestLevel(r->hierarchy, surface, r->parts, folded, r->stencils, &r->positions, &r->kinds,
                      LevelUse::kPiercedFrom, &r->folded_faces);
  for (size_t v = 0; v < before.size(); ++v) {
    if (r->positions[v] == before[v]) continue;
    r->on_faces[v] = kNoFace;
    r->creases[v] = CreasePlace();
  }
  r->untangle_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The finest level's remaining folds, with boundary vertices free to slide and
// moves off the input allowed.
void UntangleFinalFolds(const InputSurface& surface, Refinement* r) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<uint32_t> folded = std::move(r->folded_faces);
  UntangleFinestLevel(r->hierarchy, surface, r->parts, folded, r->stencils, &r->positions, &r->kinds,
                      LevelUse::kFinal, &r->folded_faces);
  r->untangle_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Normal share of the new, non-boundary vertices, per level and over all, from
// the final kinds (the untangling may have changed some).
void CountNormalVertices(const SemiRegularHierarchy& h, const std::vector<VertexKind>& kinds,
                         RemeshReport* report) {
  report->normal_fraction_per_level.clear();
  for (int level = 1; level <= h.levels(); ++level) {
    size_t normal = 0, counted = 0;
    for (uint32_t v = h.NumVertices(level - 1); v < h.NumVertices(level); ++v) {
      if (kinds[v] == VertexKind::kBoundary) continue;
      ++counted;
      normal += kinds[v] == VertexKind::kNormal;
    }
    report->normal_fraction_per_level.push_back(counted ? static_cast<double>(normal) / static_cast<double>(counted) : 1.0);
  }
  report->normal_fraction = NormalFraction(h, kinds);
}

struct RefineContext {
  const BaseDomain& base;
  const Mesh& surface_mesh;
  const ReferenceSurface& reference;  // surface_mesh, for the meter
  const InputSurface& surface;
  const RemeshOptions& options;
  double diagonal;
  DensityTarget density;
};

// Base edges whose ends lie on one crease chain, along a stretch of it nearly
// as short as the edge (CreaseCurves::SplitSite): tagged, so every level
// refines them onto the chain and the butterfly predicts along them.
std::vector<Edge> BaseEdgesAlongCreases(const InputSurface& surface, const SemiRegularHierarchy& h,
                                        const std::vector<Vec3>& positions, const std::vector<CreasePlace>& places) {
  std::vector<Edge> out;  // interior edges twice: SetBaseCreases keeps one
  if (surface.creases.empty()) return out;
  for (const Face& f : h.BaseFaces()) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = f[c], b = f[(c + 1) % 3];
      if (surface.creases.SplitSite(places[a], positions[a], places[b], positions[b])) out.push_back({a, b});
    }
  }
  return out;
}

StatusOr<Refinement> RefineAllLevels(const RefineContext& c) {
  Refinement r;
  const uint32_t nb = static_cast<uint32_t>(c.base.base_to_input.size());
  for (uint32_t v : c.base.base_to_input) {
    r.positions.push_back(c.surface_mesh.positions[v]);
    CreasePlace place;
    place.input_vertex = v;
    r.creases.push_back(place);
    const bool has_face = c.surface.face_offsets[v] < c.surface.face_offsets[v + 1];
    r.on_faces.push_back(has_face ? c.surface.vertex_faces[c.surface.face_offsets[v]] : kNoFace);
  }
  r.kinds.assign(nb, VertexKind::kBase);
  r.parts = BaseFaceParts(c.surface, c.base.base_to_input, c.base.faces);
  std::vector<ParamPoint> params = c.base.params;
  // One level at a time (Refine gives what Build would), so no level is built twice.
  EQMESH_ASSIGN_OR_RETURN(r.hierarchy, SemiRegularHierarchy::Build(nb, c.base.faces, 0));
  EQMESH_RETURN_IF_ERROR(r.hierarchy.SetBaseCreases(BaseEdgesAlongCreases(c.surface, r.hierarchy, r.positions, r.creases)));
  double previous_psnr = -std::numeric_limits<double>::infinity();
  while (true) {
    const uint64_t faces = r.hierarchy.Faces(r.levels).size();
    const LevelSize current{r.positions.size(), faces};
    // Each face gains three edge midpoints, each shared by two faces (closed
    // surfaces; boundary edges make it a little more).
    const LevelSize next{current.vertices + 3 * faces / 2, 4 * faces};
    const LevelDecision decision = NextLevel(c.options, r.levels, current, next, c.density);
    if (decision == LevelDecision::kStop) break;
    if (decision == LevelDecision::kMeasureFirst) {
      const double psnr = MeasureLevelPsnr(c.reference, r.positions, r.hierarchy.Faces(r.levels));
      if (psnr >= kAutoTargetPsnrDb || psnr - previous_psnr < kAutoMinGainDb) break;
      previous_psnr = psnr;
    }
    EQMESH_RETURN_IF_ERROR(r.hierarchy.Refine());
    ReportProgress(c.options.progress, std::string("pierce level ") + std::to_string(r.levels + 1), 0.0);
    LevelStats stats;
    r.stencils.push_back(BuildButterflyStencils(r.hierarchy, r.levels));
    RefineLevel(r.hierarchy, r.levels, c.surface, r.parts, r.stencils.back(), &r.positions, &r.on_faces, &r.kinds,
                &params, &stats, &r.creases);
    r.estimated_psnr_db_per_level.push_back(EstimatedPsnrDb(c.diagonal, stats.rms_error));
    ++r.levels;
    UntangleNewLevel(c.surface, stats.folded_faces, &r);
  }
  UntangleFinalFolds(c.surface, &r);
  return r;
}

struct SurfaceContext {
  const Prepared& prep;
  const ReferenceSurface& reference;  // prep.surface, for the meter
  const TriangleBvh& bvh;
  const InputSurface& surface;
  const RemeshOptions& options;
  DensityTarget density;
};

// Base domain, every level and the untangling, at one base error bound; adds
// each stage's seconds to the report.
StatusOr<Refinement> RemeshSurface(const SurfaceContext& c, double error_share, const std::vector<double>& bound_scale,
                                   RemeshReport* report) {
  auto lap = std::chrono::steady_clock::now();
  const auto seconds_since_lap = [&lap] {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - lap).count();
    lap = now;
    return s;
  };
  BaseDomainOptions base_options = BaseOptions(c.prep, c.options, error_share);
  base_options.bound_scale = bound_scale;
  EQMESH_ASSIGN_OR_RETURN(BaseDomain base, BuildBaseDomain(c.prep.surface, c.bvh, c.prep.boundary, base_options));
  report->stage_seconds.base_domain += seconds_since_lap();
  if (c.options.base_vertices > 0 && base.base_to_input.size() > base_options.target_vertices) {
    report->notes.push_back("simplification stalled at " + std::to_string(base.base_to_input.size()) +
                            " base vertices (asked for " + std::to_string(base_options.target_vertices) + ")");
  }
  const RefineContext refine{base,      c.prep.surface, c.reference, c.surface, c.options,
                             BoundingBoxDiagonal(c.prep.surface), c.density};
  EQMESH_ASSIGN_OR_RETURN(Refinement r, RefineAllLevels(refine));
  report->stage_seconds.refine += seconds_since_lap() - r.untangle_seconds;
  report->stage_seconds.untangle += r.untangle_seconds;
  r.input_base_face.reserve(base.params.size());
  for (const ParamPoint& p : base.params) r.input_base_face.push_back(p.face);
  return r;
}

// The floor's meter on a refinement (confirmed near the floor: kFloorConfirmDb);
// adds its seconds to the report.
double MeasureRemeshPsnr(const SurfaceContext& c, const Refinement& r, RemeshReport* report) {
  const auto measuring = std::chrono::steady_clock::now();
  const std::vector<Face>& faces = r.hierarchy.Faces(r.levels);
  double psnr = MeasureLevelPsnr(c.reference, r.positions, faces);
  if (psnr >= c.options.min_psnr && psnr < c.options.min_psnr + kFloorConfirmDb) {
    psnr = MeasureLevelPsnr(c.reference, r.positions, faces, kFloorConfirmSamples);
  }
  report->stage_seconds.measure += std::chrono::duration<double>(std::chrono::steady_clock::now() - measuring).count();
  return psnr;
}

// RemeshSurface at the automatic base bound; when the options ask for a PSNR
// floor and the remesh measures below it, again with the bound halved (up to
// kFloorRetries times), keeping the best. Where the shape has detail below the
// 2 % bound (fingers, toes, claws) the remesh loses it at every level; a floor
// that asks for that detail pays for a finer base only there.
StatusOr<Refinement> RemeshMeetingFloor(const SurfaceContext& c, RemeshReport* report) {
  const bool floor = c.options.min_psnr > 0 && c.options.base_vertices <= 0;
  double share = kBaseErrorShare;
  Refinement best;
  for (int attempt = 0;; ++attempt) {
    EQMESH_ASSIGN_OR_RETURN(Refinement r, RemeshSurface(c, share, {}, report));
    if (!floor) {
      report->base_error_share = c.options.base_vertices > 0 ? 0.0 : share;
      return r;
    }
    const double psnr = MeasureRemeshPsnr(c, r, report);
    if (attempt == 0 || psnr > report->psnr_db) {
      best = std::move(r);
      report->psnr_db = psnr;
      report->base_error_share = share;
    }
    // A finer base recovers detail lost at tips, a few dB; a floor farther off
    // is out of any base's reach, and the caller says so.
    if (report->psnr_db >= c.options.min_psnr || report->psnr_db + kFloorReachDb < c.options.min_psnr ||
        attempt == kFloorRetries) {
      return best;
    }
    char note[160];
    std::snprintf(note, sizeof(note), "remesh at a %.2g %% base bound measured %.2f dB, below the %.2f dB floor: "
                  "base bound halved", 100.0 * share, psnr, c.options.min_psnr);
    report->notes.push_back(note);
    share /= 2.0;
  }
}

// Scales the base bound by kFoldBoundScale for every input vertex whose
// parameter lies in a base face with a folded descendant; returns how many
// base faces that concerned.
size_t TightenOverFolds(const Refinement& r, std::vector<double>* scale) {
  std::vector<uint8_t> folded(r.hierarchy.BaseFaces().size(), 0);
  const int shift = 2 * r.levels;  // the faces of base face t at level L: [t * 4^L, (t + 1) * 4^L)
  for (uint32_t f : r.folded_faces) folded[f >> shift] = 1;
  for (size_t x = 0; x < scale->size(); ++x) {
    if (folded[r.input_base_face[x]]) (*scale)[x] *= kFoldBoundScale;
  }
  return static_cast<size_t>(std::count(folded.begin(), folded.end(), 1));
}

// Whether `r`, a remesh tried for fewer folds, replaces `best`: it folds fewer
// faces and, under a floor, measures at least the floor or the kept remesh,
// whichever is lower. Records `why` in the report's notes when it does.
bool KeepIfFewerFolds(const SurfaceContext& c, Refinement&& r, const std::string& why, Refinement* best,
                      RemeshReport* report) {
  if (r.folded_faces.size() >= best->folded_faces.size()) return false;
  const bool floor = c.options.min_psnr > 0;
  const double psnr = floor ? MeasureRemeshPsnr(c, r, report) : 0.0;
  if (floor && psnr < std::min(c.options.min_psnr, report->psnr_db)) return false;
  report->notes.push_back(why + ": " + std::to_string(best->folded_faces.size()) + " -> " +
                          std::to_string(r.folded_faces.size()) + " folded faces");
  *best = std::move(r);
  if (floor) report->psnr_db = psnr;
  return true;
}

// RemeshMeetingFloor, then, while the finest level still folds, up to
// kFoldRetries remeshes at the bound it kept, each with the bound tightened
// over the base faces whose descendants fold (TightenOverFolds, cumulative),
// then one with the whole bound halved (the last tightening tried still
// applied on top). Each is kept only if KeepIfFewerFolds;
// the first tightening that is not ends the tightenings (fold counts move
// chaotically with the base: diplodocus 117 -> 178 -> 381, dino 6 -> 15 -> 17,
// while cow goes 96 -> 84 -> 0 and femur 132 -> 95 -> 74;
// bench/log/2026-12-06-level-untangle.md). Folds that survive the untangling
// sit where a base face spans a part thinner than the finest level can follow
// or a crease sharper than 90 degrees; a finer base there gives those regions
// more resolution. The halving refines everything, and where the tightenings
// left folds it removes some of them more often than not (dino 6 -> 4, skull
// 2 -> 0, fandisk 1 -> 0, man 120 -> 117; bench/log/2026-12-06-fold-scan-exact.md).
StatusOr<Refinement> RemeshWithFewerFolds(const SurfaceContext& c, RemeshReport* report) {
  EQMESH_ASSIGN_OR_RETURN(Refinement best, RemeshMeetingFloor(c, report));
  if (c.options.base_vertices > 0) return best;
  std::vector<double> scale(c.prep.surface.positions.size(), 1.0);
  for (int retry = 0; retry < kFoldRetries && !best.folded_faces.empty(); ++retry) {
    const size_t regions = TightenOverFolds(best, &scale);
    EQMESH_ASSIGN_OR_RETURN(Refinement r, RemeshSurface(c, report->base_error_share, scale, report));
    const std::string why = "base bound tightened over " + std::to_string(regions) +
                            " base faces whose descendants folded";
    if (!KeepIfFewerFolds(c, std::move(r), why, &best, report)) break;
  }
  if (best.folded_faces.empty()) return best;
  const double share = report->base_error_share / 2.0;
  EQMESH_ASSIGN_OR_RETURN(Refinement r, RemeshSurface(c, share, scale, report));
  char why[96];
  std::snprintf(why, sizeof(why), "base bound halved to %.3g %% where the finest level still folded", 100.0 * share);
  if (KeepIfFewerFolds(c, std::move(r), why, &best, report)) report->base_error_share = share;
  return best;
}

// Whether the finest level of `r` is at least as dense as the input where the
// input is densest: no base face carries more input vertices (by their
// parameters) than the finest level puts in it (about half its 4^levels faces).
// The automatic count's global targets (kAutoMinVertexFactor, kAutoMaxEdgeShare)
// do not apply: a finer base one level fewer is what the caller is after, and
// the floor, which the caller checks too, holds its error.
bool DenseWhereTheInputIs(const Refinement& r) {
  std::vector<uint64_t> carried(r.hierarchy.BaseFaces().size(), 0);
  for (uint32_t t : r.input_base_face) {
    if (t < carried.size()) ++carried[t];
  }
  const uint64_t finest_per_base_face = (uint64_t{1} << (2 * r.levels)) / 2;
  return *std::max_element(carried.begin(), carried.end()) <= finest_per_base_face;
}

// Where the automatic level count's remesh still folds, the remesh again with
// one level fewer, then two (each with its own floor and fold retries), while
// one folds less, is as dense as the input where the input is densest
// (DenseWhereTheInputIs), and measures at least the floor or the kept remesh,
// whichever is lower. Why: the floor then
// asks for a finer base, whose coarse levels follow the thin parts (ears,
// horns, handles, tails) that the coarser base's levels cut across and the
// untangling cannot mend once the next level inherits them; every level fewer
// also stops four folds' worth of a fold inherited at the level above.
// Measured (bench/log/2026-12-07-fewer-levels-where-it-folds.md): cow 24 -> 0
// folded faces, femur 61 -> 7, diplodocus 80 -> 28, every remesh above 80 dB.
StatusOr<Refinement> RemeshWithFewerLevels(const SurfaceContext& c, Refinement best, RemeshReport* report) {
  if (c.options.levels >= 0 || c.options.base_vertices > 0 || !(c.options.min_psnr > 0) ||
      c.prep.input_vertices > kFoldLevelDropVertices) {
    return best;
  }
  const int automatic = best.levels;
  for (int levels = automatic - 1; levels >= std::max(1, automatic - kFoldLevelDrops); --levels) {
    if (best.folded_faces.empty()) break;
    RemeshOptions options = c.options;
    options.levels = levels;
    const SurfaceContext fewer{c.prep, c.reference, c.bvh, c.surface, options, c.density};
    RemeshReport trial;
    StatusOr<Refinement> tried = RemeshWithFewerFolds(fewer, &trial);
    // A drop is optional: one that fails leaves the remesh already made.
    if (!tried.ok()) break;
    Refinement r = std::move(tried).value();
    report->stage_seconds.base_domain += trial.stage_seconds.base_domain;
    report->stage_seconds.refine += trial.stage_seconds.refine;
    report->stage_seconds.untangle += trial.stage_seconds.untangle;
    report->stage_seconds.measure += trial.stage_seconds.measure;
    const bool kept = r.folded_faces.size() < best.folded_faces.size() && DenseWhereTheInputIs(r) &&
                      trial.psnr_db >= std::min(c.options.min_psnr, report->psnr_db);
    if (!kept) break;
    report->notes.push_back(std::to_string(best.levels) + " levels still folded " +
                            std::to_string(best.folded_faces.size()) + " faces: remeshed at " +
                            std::to_string(levels) + " levels (" + std::to_string(r.folded_faces.size()) +
                            " folded faces)");
    for (std::string& note : trial.notes) report->notes.push_back(std::move(note));
    report->psnr_db = trial.psnr_db;
    report->base_error_share = trial.base_error_share;
    best = std::move(r);
  }
  return best;
}

}  // namespace

StatusOr<SemiRegularMesh> Remesh(const Mesh& input, const RemeshOptions& options, RemeshReport* report_out) {
  const auto start = std::chrono::steady_clock::now();
  auto lap = start;
  const auto seconds_since_lap = [&lap] {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - lap).count();
    lap = now;
    return s;
  };
  RemeshReport local_report;
  RemeshReport& report = report_out ? *report_out : local_report;
  report = RemeshReport();
  if (options.levels < -1 || options.levels > kMaxLevels) {
    return InvalidArgument("levels " + std::to_string(options.levels) + " outside [-1, " +
                           std::to_string(kMaxLevels) + "]");
  }
  if (options.base_vertices < -1 || options.base_vertices == 0) {
    return InvalidArgument("base vertex count " + std::to_string(options.base_vertices) + " must be positive or -1");
  }
  EQMESH_ASSIGN_OR_RETURN(Prepared prep, Prepare(input, options, &report));
  report.input_vertices = prep.input_vertices;
  report.components_remeshed = prep.components_remeshed;
  report.components_kept_exactly = prep.components_kept;
  report.kept_exactly_vertices = prep.kept.positions.size();
  report.boundary_loops = prep.boundary_loops;

  SemiRegularMesh out;
  out.kept_exactly = prep.kept;
  if (prep.surface.faces.empty()) {
    EQMESH_ASSIGN_OR_RETURN(out.hierarchy, SemiRegularHierarchy::Build(0, {}, 0));
    report.notes.push_back("every component is too small to remesh: all kept exactly");
    report.output_vertices = prep.kept.positions.size();
    return out;
  }
  // Work at unit scale: squared lengths and areas of a 1e300-sized input would
  // overflow (and the untangler's bounded searches would become scans of the
  // whole input: a hang). A power of two keeps every result exact: base
  // vertices come back as the input's own, and inputs of ordinary size remesh
  // bit for bit as at their own scale.
  const double scale = PowerOfTwoUnitScale(prep.surface);
  for (Vec3& p : prep.surface.positions) p *= scale;
  EQMESH_ASSIGN_OR_RETURN(TriangleBvh bvh, TriangleBvh::Build(prep.surface));
  // Every remesh tried is measured against the same surface: prepared once.
  EQMESH_ASSIGN_OR_RETURN(const ReferenceSurface reference, ReferenceSurface::Build(prep.surface));
  report.stage_seconds.prepare = seconds_since_lap();
  const InputSurface surface(prep.surface, bvh, prep.boundary);
  const SurfaceContext context{prep,    reference, bvh, surface,
                               options, AutoDensityTarget(prep.surface, prep.input_vertices)};
  EQMESH_ASSIGN_OR_RETURN(Refinement folded_or_not, RemeshWithFewerFolds(context, &report));
  EQMESH_ASSIGN_OR_RETURN(Refinement best, RemeshWithFewerLevels(context, std::move(folded_or_not), &report));
  report.base_vertices = best.hierarchy.NumVertices(0);
  report.base_crease_edges = best.hierarchy.BaseCreases().size();
  CountNormalVertices(best.hierarchy, best.kinds, &report);
  out.hierarchy = std::move(best.hierarchy);
  out.positions = std::move(best.positions);
  for (Vec3& p : out.positions) p /= scale;
  out.kinds = std::move(best.kinds);
  report.levels = best.levels;
  report.estimated_psnr_db_per_level = best.estimated_psnr_db_per_level;
  report.output_vertices = out.positions.size() + out.kept_exactly.positions.size();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eqmesh

// Normal remeshing: any manifold triangle mesh (closed or with holes, one or many
// components) -> a semi-regular normal mesh over a coarse base domain whose
// vertices are input vertices.
//
// Papers: Lee, Sweldens, Schröder, Cowsar, Dobkin, "MAPS" (SIGGRAPH 1998) for the
// base domain and its parameterization; Guskov, Vidimče, Sweldens, Schröder,
// "Normal Meshes" (SIGGRAPH 2000) for the piercing. Departures are listed in
// base_domain.h and piercing.h.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// The floor `eqmesh remesh` holds a remesh to by default. At 80 dB the RMS
// distance is 1e-4 of the diagonal: a remesh of a mid-size asset that measures
// below it has lost a limb tip, a horn or a finger (the 2 % base bound leaves
// them 69-79 dB on 7 of the 18 mid-size and small meshes).
inline constexpr double kRemeshQualityFloorDb = 80.0;

struct RemeshOptions {
  // Subdivision levels. -1: automatic (refine until the finest level has 8x the
  // input's vertices and a mean edge of 1/500 of the bounding-box diagonal,
  // within 64x the input's vertices and 3 million; with a floor, on inputs of
  // up to 60k vertices, up to two fewer where the finest level folds; see
  // remesh.cpp). Range [-1, 10].
  int levels = -1;
  // Base vertices to aim for. -1: automatic: simplify while every input vertex
  // stays within 2 % of its component's diagonal of the base, down to at most
  // 0.3 % of the input vertices (see remesh.cpp and base_domain.h).
  int base_vertices = -1;
  // Run RepairForRemeshing first instead of refusing non-manifold input.
  bool repair = false;
  // PSNR floor (dB, the `eqmesh compare` meter) for the automatic base: a remesh
  // measuring below it (by at most 20 dB) is redone with the base's error bound
  // halved, up to four times, and the best is kept (it may still be below). 0:
  // no floor, nothing measured. `eqmesh remesh` asks for kRemeshQualityFloorDb;
  // encoders pass their PSNR target plus a margin.
  double min_psnr = 0.0;
  ProgressFn progress;
};

struct RemeshReport {
  size_t input_vertices = 0;   // referenced vertices of the surface remeshed (after welding)
  // Input vertices merged into another at the same position (WeldSeams, or the
  // repair's weld with RemeshOptions::repair).
  size_t welded_vertices = 0;
  size_t base_vertices = 0;
  // Base edges tagged as creases (semi_regular.h): those along the input's
  // crease chains, which every level follows.
  size_t base_crease_edges = 0;
  size_t output_vertices = 0;  // finest level (plus kept_exactly vertices)
  int levels = 0;
  // Share of new (odd), non-boundary vertices that are normal, over all levels.
  double normal_fraction = 0.0;
  std::vector<double> normal_fraction_per_level;  // refinement j -> j+1 at [j]
  // Remesh error estimated during refinement (input vertices to the remesh), per level.
  std::vector<double> estimated_psnr_db_per_level;
  size_t components_remeshed = 0;
  size_t components_kept_exactly = 0;
  size_t kept_exactly_vertices = 0;
  // The automatic base's error bound (share of each part's diagonal; 0 with
  // base_vertices), and with RemeshOptions::min_psnr the remesh's PSNR against
  // the input (100k samples each way; 0 when not measured).
  double base_error_share = 0.0;
  double psnr_db = 0.0;
  size_t boundary_loops = 0;
  double seconds = 0.0;
  // Wall seconds of each stage, so speed work knows where the time goes.
  struct StageSeconds {
    double prepare = 0.0;      // checks, components, unit scale, search tree
    double base_domain = 0.0;  // simplification and parameterization
    double refine = 0.0;       // piercing of every level
    double untangle = 0.0;
    double measure = 0.0;      // the floor's PSNR measurements (RemeshOptions::min_psnr)
  } stage_seconds;
  std::vector<std::string> notes;
};

StatusOr<SemiRegularMesh> Remesh(const Mesh& input, const RemeshOptions& options,
                                 RemeshReport* report);

}  // namespace eqmesh

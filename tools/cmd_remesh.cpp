// eqmesh remesh IN OUT: irregular manifold mesh -> semi-regular normal mesh
// (finest level written as a plain mesh). Thin layer over Remesh() (lib/remesh).
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mesh_io/mesh_io.h"
#include "mesh_io/semi_regular_io.h"
#include "mesh/semi_regular.h"
#include "remesh/remesh.h"
#include "mesh/diagnose.h"
#include "mesh/repair.h"
#include "metrics/surface_distance.h"
#include "remesh/quality_checks.h"
#include "core/thread_count.h"
#include "tools/command.h"
#include "tools/terminal_progress.h"

namespace {

constexpr const char* kName = "remesh";


int RunRemesh(int argc, char** argv) {
  CLI::App app{"Remesh a manifold triangle mesh into a semi-regular normal mesh", argv[0]};
  std::string in_path, out_path;
  int levels = -1, base_vertices = -1;
  double min_psnr = eqmesh::kRemeshQualityFloorDb;
  bool repair = false, json = false;
  int threads = 0;
  app.add_option("IN", in_path, "input mesh (.obj .ply .off .gltf .glb, optionally .gz)")->required();
  app.add_option("OUT", out_path,
                 "output: finest level as a mesh (.obj .ply .off .glb), or the whole hierarchy as a "
                 "lossless .srm file that `eqmesh encode` reads without remeshing again")
      ->required();
  app.add_option("--levels", levels,
                 "subdivision levels (-1: automatic: 8x the input's density, then more while the remesh "
                 "measures below 86 dB)")
      ->check(CLI::Range(-1, 10));
  app.add_option("--base-vertices", base_vertices,
                 "base mesh size to simplify to (-1: automatic, sized by the shape: every input vertex "
                 "within 2 % of its part's diagonal of the base)")
      ->check(CLI::Range(-1, 1 << 30));
  app.add_option("--min-psnr", min_psnr,
                 "with the automatic base: when the remesh measures below this many dB against the input "
                 "(by at most 20 dB), redo it with a base twice as fine, up to four times, keeping the best "
                 "(default 80; 0: no floor, nothing measured)")
      ->check(CLI::Range(0.0, 300.0));
  app.add_flag("--repair", repair, "repair non-manifold / misoriented input instead of refusing it");
  app.add_flag("--json", json, "print one JSON object with the remesh report");
  app.add_option("--threads", threads, "worker threads, 0 = all cores (the output does not depend on it)")
      ->check(CLI::Range(0, 256));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  eqmesh::SetWorkerThreadLimit(threads);
  if (eqmesh::IsSameFile(in_path, out_path)) return eqmesh::cli::Fail(kName, out_path + ": is the input file; write the output elsewhere");
  if (base_vertices == 0) return eqmesh::cli::Fail(kName, "--base-vertices must be positive or -1");

  eqmesh::ReadReport read_report;
  auto mesh = eqmesh::ReadMesh(in_path, &read_report);
  if (!mesh.ok()) return eqmesh::cli::Fail(kName, mesh.status().message());
  // Repaired here rather than by Remesh(): the fold count below is taken against
  // the surface remeshed (with --repair inward components face out), and one
  // repair serves both.
  std::optional<eqmesh::Mesh> repaired;
  eqmesh::RepairReport repair_report;
  if (repair) {
    auto r = eqmesh::RepairForRemeshing(*mesh, &repair_report);
    if (!r.ok()) return eqmesh::cli::Fail(kName, in_path + ": " + r.status().message());
    repaired = std::move(r).value();
  }
  const eqmesh::Mesh& remesh_input = repaired ? *repaired : *mesh;
  // Unrepaired input Remesh() welds itself (WeldSeams); the fold count judges
  // each face against that welded surface, whose components are its parts.
  const eqmesh::Mesh surface = repaired ? *repaired : eqmesh::WeldSeams(*mesh);
  eqmesh::RemeshOptions options;
  options.levels = levels;
  options.base_vertices = base_vertices;
  options.min_psnr = min_psnr;
  options.progress = eqmesh::cli::TerminalProgress(json);
  eqmesh::RemeshReport report;
  auto remeshed = eqmesh::Remesh(remesh_input, options, &report);
  eqmesh::cli::ClearTerminalProgress(options.progress);
  if (!remeshed.ok()) return eqmesh::cli::Fail(kName, in_path + ": " + remeshed.status().message());
  if (!repair_report.Unchanged()) report.notes.insert(report.notes.begin(), "repair: " + repair_report.Summary());
  if (report.psnr_db > 0 && report.psnr_db < options.min_psnr) {
    // Still written: the best remesh found is worth having, but not silently.
    std::fprintf(stderr,
                 "eqmesh remesh: warning: the remesh measures %.2f dB against the input, below the %.0f dB floor "
                 "even with the base bound at %.3g %% (try --base-vertices)\n",
                 report.psnr_db, options.min_psnr, 100.0 * report.base_error_share);
  }
  const eqmesh::Mesh finest = eqmesh::ExtractLevel(*remeshed, remeshed->hierarchy.levels());
  const eqmesh::Status written = eqmesh::cli::EndsWith(out_path, ".srm")
                                      ? eqmesh::WriteSemiRegular(*remeshed, out_path)
                                      : eqmesh::WriteMesh(finest, out_path);
  if (!written.ok()) return eqmesh::cli::Fail(kName, written.message());
  if (!json) {
    std::printf("%s: %zu input vertices -> base %zu, %d levels, %zu vertices, normal %.2f%%, %.2f s\n",
                out_path.c_str(), report.input_vertices, report.base_vertices, report.levels,
                report.output_vertices, 100.0 * report.normal_fraction, report.seconds);
    return 0;
  }
  nlohmann::json j;
  j["input"] = in_path;
  j["output"] = out_path;
  j["input_vertices"] = report.input_vertices;
  j["input_faces"] = mesh->faces.size();
  j["welded_vertices"] = report.welded_vertices;
  j["base_vertices"] = report.base_vertices;
  j["base_crease_edges"] = report.base_crease_edges;
  j["levels"] = report.levels;
  j["output_vertices"] = report.output_vertices;
  j["output_faces"] = finest.faces.size();
  j["normal_fraction"] = report.normal_fraction;
  j["normal_fraction_per_level"] = report.normal_fraction_per_level;
  j["estimated_psnr_db_per_level"] = report.estimated_psnr_db_per_level;
  j["components_remeshed"] = report.components_remeshed;
  j["components_kept_exactly"] = report.components_kept_exactly;
  j["kept_exactly_vertices"] = report.kept_exactly_vertices;
  j["boundary_loops"] = report.boundary_loops;
  j["base_error_share"] = report.base_error_share;
  j["seconds"] = report.seconds;
  j["stage_seconds"] = {{"prepare", report.stage_seconds.prepare},
                        {"base_domain", report.stage_seconds.base_domain},
                        {"refine", report.stage_seconds.refine},
                        {"untangle", report.stage_seconds.untangle},
                        {"measure", report.stage_seconds.measure}};
  // Original first: its bounding-box diagonal is the PSNR peak.
  auto cmp = eqmesh::CompareSurfaces(*mesh, finest, eqmesh::CompareOptions());
  if (cmp.ok()) {
    j["psnr_db"] = cmp->psnr_db;
    j["hausdorff"] = cmp->hausdorff;
  } else {
    report.notes.push_back("psnr not measured: " + cmp.status().message());
  }
  auto folds = eqmesh::CountFoldsAgainstInput(finest, surface);
  if (folds.ok()) {
    j["flipped_faces"] = folds->flipped_faces;
    j["flipped_near_self_crossings"] = folds->flipped_near_self_crossings;
    j["degenerate_faces"] = folds->degenerate_faces;
    if (folds->flipped_near_self_crossings > 0) {
      report.notes.push_back(std::to_string(folds->flipped_near_self_crossings) + " of the " +
                             std::to_string(folds->flipped_faces) +
                             " flipped faces lie within 3 of their edges of where the input passes through itself "
                             "(`eqmesh info`: self_crossing_faces)");
    }
  }
  j["sliver_faces"] = eqmesh::CountSlivers(finest);
  const eqmesh::MeshDiagnosis in_diag = eqmesh::Diagnose(*mesh);
  const eqmesh::MeshDiagnosis out_diag = eqmesh::Diagnose(finest);
  j["input_closed_genus"] = in_diag.closed_genus;
  j["output_closed_genus"] = out_diag.closed_genus;
  j["input_boundary_loops"] = in_diag.boundary_loops;
  j["output_boundary_loops"] = out_diag.boundary_loops;
  j["output_manifold"] = out_diag.IsManifold() && out_diag.inconsistent_edges == 0;
  j["notes"] = report.notes;
  std::printf("%s\n", j.dump().c_str());
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("remesh", "remesh a manifold mesh into a semi-regular normal mesh", RunRemesh);

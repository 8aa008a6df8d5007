// eqmesh compare IN OTHER: Metro-style symmetric surface distance and
// PSNR (peak = ORIGINAL's bounding-box diagonal). See lib/metrics/surface_distance.h.
#include <cctype>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "gltf/gltf_loader.h"
#include "gltf/surface_color.h"
#include "mesh_io/mesh_io.h"
#include "metrics/color_distance.h"
#include "core/parallel_blocks.h"
#include "metrics/surface_distance.h"
#include "remesh/quality_checks.h"
#include "tools/command.h"
#include "tools/gltf_info.h"

namespace eqmesh::cli {
namespace {

struct CompareArgs {
  std::string original, other;
  uint64_t samples = 0;
  uint64_t seed = CompareOptions{}.seed;
  int threads = 0;
  bool folds = false;
  bool json = false;
};

struct CompareRun {
  SurfaceDistance d;
  std::optional<ColorDistance> color;  // when both inputs are glTF and one is coloured
  std::optional<FoldReport> folds;     // with --folds
  size_t faces_original = 0, faces_other = 0;
  double read_seconds = 0.0, compare_seconds = 0.0;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Reads and validates one input; the error names the file exactly once.
StatusOr<Mesh> LoadForCompare(const std::string& path) {
  StatusOr<Mesh> mesh = ReadMeshDecodingGltf(path);
  Status status = mesh.ok() ? ValidateForCompare(*mesh) : mesh.status();
  if (status.ok()) return mesh;
  if (status.message().find(path) == std::string::npos) status = status.WithContext(path);
  return status;
}

bool IsGltfPath(std::string path) {
  for (char& c : path) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return EndsWith(path, ".glb") || EndsWith(path, ".gltf");
}

StatusOr<gltf::ColoredScene> LoadColored(const std::string& path) {
  auto model = gltf::LoadGltf(path);
  if (!model.ok()) return model.status();
  auto scene = gltf::FlattenWithColor(*model);
  if (!scene.ok()) return scene.status().WithContext(path);
  return scene;
}

// The appearance meter on the geometry's samples: for two glTF scenes of which at
// least one has a texture or COLOR_0 (else there is nothing to compare).
StatusOr<std::optional<ColorDistance>> CompareSceneColors(const CompareArgs& args, uint64_t samples) {
  if (!IsGltfPath(args.original) || !IsGltfPath(args.other)) return std::optional<ColorDistance>();
  EQMESH_ASSIGN_OR_RETURN(const gltf::ColoredScene a, LoadColored(args.original));
  EQMESH_ASSIGN_OR_RETURN(const gltf::ColoredScene b, LoadColored(args.other));
  if (!a.varies && !b.varies) return std::optional<ColorDistance>();
  EQMESH_ASSIGN_OR_RETURN(const ColorDistance d,
                          CompareColors(a.mesh, a.color, b.mesh, b.color, {samples, args.seed, args.threads}));
  return std::optional<ColorDistance>(d);
}

// JSON has no infinity: an exact match (rms 0) reports psnr_db as null.
nlohmann::json FiniteOrNull(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json ToJson(const CompareArgs& args, const CompareRun& run) {
  const SurfaceDistance& d = run.d;
  nlohmann::json j;
  j["original"] = args.original;
  j["other"] = args.other;
  j["faces_original"] = run.faces_original;
  j["faces_other"] = run.faces_other;
  j["rms_ab"] = d.rms_ab;
  j["rms_ba"] = d.rms_ba;
  j["rms"] = d.rms;
  j["mean_ab"] = d.mean_ab;
  j["mean_ba"] = d.mean_ba;
  j["mean"] = d.mean;
  j["hausdorff_ab"] = d.hausdorff_ab;
  j["hausdorff_ba"] = d.hausdorff_ba;
  j["hausdorff"] = d.hausdorff;
  j["bbox_diagonal"] = d.bbox_diagonal;
  j["psnr_db"] = FiniteOrNull(d.psnr_db);
  if (run.color) {
    j["color_rms"] = run.color->rms;
    j["color_rms_ab"] = run.color->rms_ab;
    j["color_rms_ba"] = run.color->rms_ba;
    j["color_psnr_db"] = FiniteOrNull(run.color->psnr_db);
  }
  if (run.folds) {
    j["flipped_faces"] = run.folds->flipped_faces;
    j["flipped_near_self_crossings"] = run.folds->flipped_near_self_crossings;
    j["degenerate_faces"] = run.folds->degenerate_faces;
  }
  j["samples"] = d.samples;
  j["seed"] = args.seed;
  j["threads"] = ResolveThreadCount(args.threads);
  j["read_seconds"] = run.read_seconds;
  j["compare_seconds"] = run.compare_seconds;
  j["seconds"] = run.read_seconds + run.compare_seconds;
  return j;
}

void PrintTable(const CompareArgs& args, const CompareRun& run) {
  const SurfaceDistance& d = run.d;
  std::printf("original   %s (%zu faces)\n", args.original.c_str(), run.faces_original);
  std::printf("other      %s (%zu faces)\n", args.other.c_str(), run.faces_other);
  std::printf("samples    %" PRIu64 " per direction, seed %" PRIu64 ", %d threads\n", d.samples,
              args.seed, ResolveThreadCount(args.threads));
  std::printf("%-10s %14s %14s %14s\n", "", "orig->other", "other->orig", "symmetric");
  std::printf("%-10s %14.6e %14.6e %14.6e\n", "rms", d.rms_ab, d.rms_ba, d.rms);
  std::printf("%-10s %14.6e %14.6e %14.6e\n", "mean", d.mean_ab, d.mean_ba, d.mean);
  std::printf("%-10s %14.6e %14.6e %14.6e\n", "hausdorff", d.hausdorff_ab, d.hausdorff_ba, d.hausdorff);
  std::printf("bbox diag  %.6g (original)\n", d.bbox_diagonal);
  std::printf("rms/diag   %.6e\n", d.rms / d.bbox_diagonal);
  if (std::isfinite(d.psnr_db)) {
    std::printf("psnr       %.3f dB\n", d.psnr_db);
  } else {
    std::printf("psnr       inf (surfaces identical at every sample)\n");
  }
  if (run.color) {
    std::printf("colour     rms %.3f of 255 (%.3f / %.3f), psnr %.3f dB\n", run.color->rms, run.color->rms_ab,
                run.color->rms_ba, run.color->psnr_db);
  }
  if (run.folds) {
    std::printf("folds      %zu flipped (%zu near where IN crosses itself), %zu degenerate of OTHER's %zu faces\n",
                run.folds->flipped_faces, run.folds->flipped_near_self_crossings, run.folds->degenerate_faces,
                run.faces_other);
  }
  std::printf("seconds    %.3f (read %.3f, compare %.3f)\n", run.read_seconds + run.compare_seconds,
              run.read_seconds, run.compare_seconds);
}

int RunCompare(int argc, char** argv) {
  CLI::App app{
      "Metro-style surface distance between IN and OTHER: area-uniform samples on each\n"
      "surface, distance to the closest point of the other. RMS = max of the two directions;\n"
      "PSNR = 20 log10(bbox diagonal of IN / RMS). Two glTF scenes of which one is textured or\n"
      "coloured also get the colour error on the same samples (RGB against the closest point's,\n"
      "peak 255, the worse direction: color_psnr_db). Results do not depend on --threads."};
  CompareArgs args;
  app.add_option("IN", args.original,
                 "reference mesh, e.g. the original (its bbox diagonal is the PSNR peak); any input format, "
                 "a compressed glTF is decoded first")
      ->required();
  app.add_option("OTHER", args.other, "mesh to measure against IN (same formats)")->required();
  app.add_option("--samples", args.samples,
                 "samples per direction (default: 10 x IN's vertex count, clamped to 1M..20M; limit 1e9)")
      ->check(CLI::NonNegativeNumber);  // else "-5" wraps to 2^64 - 5
  app.add_option("--seed", args.seed, "sampling seed (same seed, same numbers)")->check(CLI::NonNegativeNumber);
  app.add_option("--threads", args.threads, "worker threads, 0 = all cores")->check(CLI::Range(0, 1024));
  app.add_flag("--folds", args.folds,
               "also count OTHER's flipped faces (normal opposed to that of IN's face nearest the face's "
               "centroid, each connected part of OTHER against the part of IN it lies on: the test behind "
               "`remesh --json`'s flipped_faces), how many of those lie within 3 of their edges of a place where IN "
               "passes through itself, and OTHER's degenerate faces");
  app.add_flag("--json", args.json, "print one JSON object instead of a table");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  CompareRun run;
  const auto read_start = std::chrono::steady_clock::now();
  StatusOr<Mesh> a = LoadForCompare(args.original);
  if (!a.ok()) return Fail("compare", a.status().message());
  StatusOr<Mesh> b = LoadForCompare(args.other);
  if (!b.ok()) return Fail("compare", b.status().message());
  run.read_seconds = SecondsSince(read_start);
  run.faces_original = a->num_faces();
  run.faces_other = b->num_faces();
  const auto compare_start = std::chrono::steady_clock::now();
  StatusOr<SurfaceDistance> d = CompareSurfaces(*a, *b, {args.samples, args.seed, args.threads});
  if (!d.ok()) return Fail("compare", args.original + " vs " + args.other + ": " + d.status().message());
  run.d = *d;
  auto color = CompareSceneColors(args, d->samples);
  if (!color.ok()) return Fail("compare", args.original + " vs " + args.other + ": colour: " + color.status().message());
  run.color = *color;
  if (args.folds) {
    StatusOr<FoldReport> folds = CountFoldsAgainstInput(*b, *a);
    if (!folds.ok()) return Fail("compare", args.original + " vs " + args.other + ": folds: " + folds.status().message());
    run.folds = *folds;
  }
  run.compare_seconds = SecondsSince(compare_start);
  if (args.json) {
    std::printf("%s\n", ToJson(args, run).dump(2).c_str());
  } else {
    PrintTable(args, run);
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("compare", "Metro surface distance (RMS, Hausdorff, PSNR) between two meshes",
                        RunCompare);

}  // namespace eqmesh::cli

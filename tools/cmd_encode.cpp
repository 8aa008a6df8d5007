// eqmesh encode IN OUT.eqm: read -> normal remesh -> wavelet + EQ (closed loop),
// zerotree (embedded, open loop) or uniform coding, at a lambda, a bits-per-vertex
// target or a PSNR target.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "coding/encoder.h"
#include "coding/level_count_search.h"
#include "coding/representation_choice.h"
#include "gltf/gltf_converter.h"
#include "mesh_io/mesh_io.h"
#include "mesh_io/semi_regular_io.h"
#include "remesh/remesh.h"
#include "core/thread_count.h"
#include "tools/command.h"
#include "tools/terminal_progress.h"

namespace eqmesh::cli {
namespace {

constexpr const char* kName = "encode";

const char* TransformName(bitstream::TransformId transform) {
  return transform == bitstream::TransformId::kLifted ? "lifted" : "unlifted";
}

struct EncodeArgs {
  std::string in_path, out_path;
  double bpv = 0, lambda = 0, psnr = 0, tangential_factor = 0.0;
  // The library's default transform (encoder.h says why), so the two cannot drift apart.
  std::string transform = TransformName(EncodeOptions().transform), coder = "eq";
  std::string original_path;
  int levels = -1, base_vertices = -1;
  int threads = 0;
  double min_psnr = 60.0;
  int texture_size = 0;
  int64_t max_triangles = -1;
  bool strict = false;
  bool repair = false, measure = false, json = false, fallback = false;
  bool draco_base = false;
};

// What the encoder starts from: a semi-regular mesh (remeshed here, or read
// from a .srm file) and, when known, the original mesh it approximates.
struct Source {
  SemiRegularMesh remeshed;
  std::optional<Mesh> original;
  RemeshReport remesh;
  RemeshOptions remesh_options;  // of `remeshed` (none for a .srm input)
  double remesh_seconds = 0;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Below this, a --bpv stream is worth a warning when the remesh itself is the
// limit (and not the rate): the input is then no good fit for eqmesh.
constexpr double kLowCeilingDb = 70.0;

void WarnOnLowCeiling(const SemiRegularMesh& remeshed, const Mesh& original) {
  const StatusOr<double> ceiling = RemeshCeilingPsnr(remeshed, original);
  if (ceiling.ok() && *ceiling < kLowCeilingDb) {
    std::fprintf(stderr,
                 "eqmesh encode: warning: the remesh itself measures only %.2f dB against the input (below %.0f dB): "
                 "no rate gets closer; Draco may serve this mesh better\n",
                 *ceiling, kLowCeilingDb);
  }
}

EncodeOptions ToEncodeOptions(const EncodeArgs& a) {
  EncodeOptions o;
  o.transform = a.transform == "unlifted" ? bitstream::TransformId::kUnlifted
                                          : bitstream::TransformId::kLifted;
  o.coder = a.coder == "uniform"    ? bitstream::CoderId::kUniform
            : a.coder == "zerotree" ? bitstream::CoderId::kZerotree
                                    : bitstream::CoderId::kEq;
  if (a.lambda > 0) o.lambda = a.lambda;
  o.target_bpv = a.bpv;
  o.target_psnr = a.psnr;
  o.tangential_factor = a.tangential_factor;
  o.measure_psnr = a.measure;
  o.draco_base = a.draco_base;
  o.max_triangles = a.max_triangles < 0 ? 0 : static_cast<uint64_t>(a.max_triangles);
  return o;
}

nlohmann::json ToJson(const EncodeArgs& a, const RemeshReport& remesh, const EncodeReport& r,
                      const LevelCountReport& search, const RepresentationReport& choice, double remesh_seconds,
                      double encode_seconds) {
  nlohmann::json j;
  j["input"] = a.in_path;
  j["output"] = a.out_path;
  j["input_vertices"] = remesh.input_vertices;
  j["welded_vertices"] = remesh.welded_vertices;
  j["representation"] = choice.as_is ? "as_is" : "normal_mesh";
  if (choice.tried_as_is) {
    j["representations"] = {{"normal_mesh", {{"bytes", choice.remeshed_bytes}, {"psnr_db", choice.remeshed_psnr_db}}},
                            {"as_is", {{"bytes", choice.as_is_bytes}, {"psnr_db", choice.as_is_psnr_db}}}};
  }
  j["base_vertices"] = choice.as_is ? choice.as_is_vertices : remesh.base_vertices;
  j["semi_regular_vertices"] = choice.as_is ? choice.as_is_vertices : remesh.output_vertices;
  j["remesh_levels"] = remesh.levels;
  if (!choice.base_sizes_tried.empty()) j["base_sizes_tried"] = choice.base_sizes_tried;
  j["levels"] = r.level_bytes.size();
  j["level_search"] = nlohmann::json::array();
  for (const LevelCountTrial& t : search.trials) {
    j["level_search"].push_back({{"levels", t.levels}, {"bpv", t.bpv}, {"psnr_db", t.psnr_db}, {"coded", t.coded}});
  }
  j["transform"] = a.transform;
  j["coder"] = a.coder;
  j["bytes"] = r.total_bytes;
  j["bpv"] = r.bpv;
  j["lambda"] = r.lambda;
  j["tangential_factor"] = r.tangential_factor;
  j["base_bits"] = r.base_bits;
  j["header_bytes"] = r.header_bytes;
  j["base_bytes"] = r.base_bytes;
  j["base_coder"] = r.base_compact ? "compact" : "draco";
  j["base_tangential_step"] = r.base_tangential_step;
  j["kept_bytes"] = r.kept_bytes;
  j["level_bytes"] = r.level_bytes;
  j["rate_evaluations"] = r.rate_evaluations;
  j["remesh_seconds"] = remesh_seconds;
  j["encode_seconds"] = encode_seconds;
  j["seconds"] = remesh_seconds + encode_seconds;
  if (r.psnr_measured) j["psnr_db"] = r.psnr_db;
  return j;
}

nlohmann::json ToJson(const gltf::PrimitiveOutcome& p) {
  nlohmann::json j;
  j["mesh"] = p.mesh;
  j["primitive"] = p.primitive;
  j["compressed"] = p.compressed;
  if (!p.compressed) j["reason"] = p.reason;
  j["input_vertices"] = p.input_vertices;
  j["output_vertices"] = p.output_vertices;
  j["stream_bytes"] = p.stream_bytes;
  j["levels"] = p.levels;
  if (p.compressed) j["representation"] = p.as_is ? "as_is" : "normal_mesh";
  if (p.psnr_db > 0) j["psnr_db"] = p.psnr_db;
  if (!p.note.empty()) j["note"] = p.note;
  return j;
}

// One line for the file, one per compressed primitive. A --bpv or --psnr target
// applies to each primitive's stream (bits per input vertex of that primitive);
// the file adds the glTF JSON and container around the streams.
void PrintGlbSummary(const std::string& out_path, const gltf::ConvertReport& report) {
  uint64_t streams = 0;
  for (const auto& p : report.primitives) streams += p.compressed ? p.stream_bytes : 0;
  std::printf("%s: %llu bytes (%llu in streams), %zu primitive(s) compressed, %zu unchanged\n", out_path.c_str(),
              static_cast<unsigned long long>(report.output_bytes), static_cast<unsigned long long>(streams),
              report.compressed, report.unchanged);
  for (const auto& p : report.primitives) {
    if (!p.compressed) continue;
    std::printf("  mesh %d primitive %d: %zu vertices -> %llu-byte stream, %.3f bits per input vertex, %s",
                p.mesh, p.primitive, p.input_vertices, static_cast<unsigned long long>(p.stream_bytes),
                p.input_vertices ? 8.0 * static_cast<double>(p.stream_bytes) / static_cast<double>(p.input_vertices) : 0.0,
                p.as_is ? ("coded as is at " + std::to_string(p.output_vertices) + " vertices").c_str()
                        : (std::to_string(p.levels) + " levels").c_str());
    if (p.psnr_db > 0) std::printf(", PSNR %.2f dB", p.psnr_db);
    std::printf("\n");
    if (!p.note.empty()) std::fprintf(stderr, "eqmesh encode: warning: mesh %d primitive %d %s\n", p.mesh, p.primitive,
                                      p.note.c_str());
  }
}

// glTF output: every remeshable TRIANGLES primitive becomes an
// EXT_normal_mesh_compression stream; the rest of the scene is kept.
int EncodeToGlb(const EncodeArgs& a) {
  gltf::ConvertOptions options;
  options.codec = ToEncodeOptions(a);
  options.remesh.levels = a.levels;
  options.remesh.base_vertices = a.base_vertices;
  options.remesh.repair = a.repair;
  options.fallback = a.fallback;
  options.strict = a.strict;
  options.min_psnr = a.min_psnr;
  options.texture_size = static_cast<uint32_t>(a.texture_size);
  options.max_triangles = a.max_triangles;
  options.remesh.progress = TerminalProgress(a.json);
  options.codec.progress = options.remesh.progress;
  const auto start = std::chrono::steady_clock::now();
  auto report = gltf::ConvertToCompressedGltf(a.in_path, a.out_path, options);
  ClearTerminalProgress(options.remesh.progress);
  if (!report.ok()) {
    const std::string& m = report.status().message();
    return Fail(kName, m.find(a.in_path) == std::string::npos ? a.in_path + ": " + m : m);
  }
  for (const auto& p : report->primitives) {
    if (!p.compressed) {
      std::fprintf(stderr, "eqmesh encode: %s: mesh %d primitive %d left unchanged: %s\n", a.in_path.c_str(), p.mesh,
                   p.primitive, p.reason.c_str());
    }
  }
  if (a.json) {
    nlohmann::json j;
    j["input"] = a.in_path;
    j["output"] = a.out_path;
    j["compressed"] = report->compressed;
    j["unchanged"] = report->unchanged;
    j["input_bytes"] = report->input_bytes;
    j["bytes"] = report->output_bytes;
    j["primitives"] = nlohmann::json::array();
    for (const auto& p : report->primitives) j["primitives"].push_back(ToJson(p));
    j["seconds"] = SecondsSince(start);
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    PrintGlbSummary(a.out_path, *report);
  }
  return 0;
}

// The stream and glTF store float32 positions, and a .glb output reads its input
// through float32 accessors: rounding here makes `encode IN x.eqm` and `encode IN
// x.glb` code the same geometry into the same stream. Coordinates beyond float32
// range stay as they are, for the encoder to refuse by name.
void RoundToFloat32(Mesh* mesh) {
  for (Vec3& p : mesh->positions) {
    for (int k = 0; k < 3; ++k) {
      if (std::abs(p[k]) <= static_cast<double>(std::numeric_limits<float>::max())) {
        p[k] = static_cast<double>(static_cast<float>(p[k]));
      }
    }
  }
}

StatusOr<Source> RemeshInput(const EncodeArgs& a) {
  Source src;
  EQMESH_ASSIGN_OR_RETURN(Mesh mesh, ReadMesh(a.in_path));
  RoundToFloat32(&mesh);
  RemeshOptions options;
  options.levels = a.levels;
  options.base_vertices = a.base_vertices;
  options.repair = a.repair;
  if (a.psnr > 0) options.min_psnr = a.psnr + kRemeshMarginDb;
  options.progress = TerminalProgress(a.json);
  const auto start = std::chrono::steady_clock::now();
  auto remeshed = Remesh(mesh, options, &src.remesh);
  ClearTerminalProgress(options.progress);
  if (!remeshed.ok()) return remeshed.status().WithContext(a.in_path);
  src.remesh_seconds = SecondsSince(start);
  src.remesh_options = options;
  src.remeshed = std::move(*remeshed);
  src.original = std::move(mesh);
  return src;
}

// A .srm from `eqmesh remesh` skips remeshing; --original names the mesh it
// came from (needed for bpv, PSNR targets, --measure and the level search).
StatusOr<Source> ReadSemiRegularInput(const EncodeArgs& a) {
  Source src;
  EQMESH_ASSIGN_OR_RETURN(src.remeshed, ReadSemiRegular(a.in_path));
  if (!a.original_path.empty()) {
    EQMESH_ASSIGN_OR_RETURN(Mesh original, ReadMesh(a.original_path));
    src.original = std::move(original);
    src.remesh.input_vertices = CountReferencedVertices(*src.original);
  } else if (a.bpv > 0 || a.psnr > 0 || a.measure) {
    return InvalidArgument(a.in_path + ": --bpv, --psnr and --measure on a .srm input need --original MESH");
  }
  const SemiRegularHierarchy& h = src.remeshed.hierarchy;
  src.remesh.base_vertices = h.NumVertices(0);
  src.remesh.levels = h.levels();
  src.remesh.output_vertices = src.remeshed.positions.size() + src.remeshed.kept_exactly.positions.size();
  return src;
}

int RunEncode(int argc, char** argv) {
  CLI::App app{"Encode a mesh into an eqmesh stream (.eqm)", argv[0]};
  EncodeArgs a;
  app.add_option("IN", a.in_path,
                 "input mesh (.obj .ply .off .gltf .glb, optionally .gz), or a .srm semi-regular file "
                 "written by `eqmesh remesh` (no remeshing)")
      ->required();
  app.add_option("OUT", a.out_path, "output: .eqm stream, or .glb with EXT_normal_mesh_compression")->required();
  auto* bpv = app.add_option("--bpv", a.bpv, "target bits per input vertex (within 3 %)")
                  ->check(CLI::Range(1e-3, 1e4));
  auto* lambda = app.add_option("--lambda", a.lambda,
                                "rate-distortion trade-off instead of a target: larger keeps more detail, a bigger "
                                "stream with less error (on a scan, 4x the value gives roughly twice the bytes and "
                                "4 dB); typical 1e-4 to 1, default 1/64")
                     ->check(CLI::Range(1e-30, 1e30));
  auto* psnr = app.add_option("--psnr", a.psnr, "smallest stream whose PSNR meets this many dB")
                   ->check(CLI::Range(1.0, 300.0));
  bpv->excludes(lambda)->excludes(psnr);
  lambda->excludes(psnr);
  app.add_option("--transform", a.transform,
                 std::string("butterfly wavelet: lifted | unlifted (default: ") + a.transform + ")")
      ->check(CLI::IsMember({"unlifted", "lifted"}));
  app.add_option("--coder", a.coder,
                 "coefficient coder: eq | zerotree (embedded, PGC baseline; --bpv cuts it exactly, "
                 "--lambda picks its last bit plane) | uniform (baseline)")
      ->check(CLI::IsMember({"eq", "zerotree", "uniform"}));
  app.add_option("--tangential-factor", a.tangential_factor,
                 "how much cheaper than the normal part the two tangential parts of each wavelet "
                 "coefficient are coded (they matter less to the surface: a larger F spends fewer bits "
                 "on them; default 4 lifted, 2 unlifted)")
      ->check(CLI::Range(1e-6, 1e6));
  app.add_option("--levels", a.levels, "subdivision levels (-1: automatic)")->check(CLI::Range(-1, 10));
  app.add_option("--base-vertices", a.base_vertices,
                 "base mesh size to aim for (-1: automatic; with --psnr or --bpv the encoder also tries twice and "
                 "half the remesher's size, and further while each does better)")
      ->check(CLI::Range(-1, 1 << 30));
  app.add_flag("--repair", a.repair, "repair non-manifold / misoriented input instead of refusing it");
  app.add_flag("--draco-base", a.draco_base,
               "code the base mesh with Draco instead of the compact base chunk (streams that "
               "version 1.1 decoders read; larger)");
  app.add_flag("--measure", a.measure, "decode the stream and report its PSNR against the input");
  app.add_option("--original", a.original_path,
                 ".srm input: the mesh it was remeshed from (PSNR reference and bpv denominator)");
  app.add_flag("--fallback", a.fallback,
               ".glb output: also store uncompressed geometry for loaders without the extension");
  app.add_flag("--json", a.json, "print one JSON object with the report");
  app.add_flag("--strict", a.strict,
               ".glb output: fail when any triangle primitive cannot be compressed (default: keep it "
               "unchanged and warn; the run fails anyway when none could be compressed)");
  app.add_option("--min-psnr", a.min_psnr,
                 ".glb output: leave a primitive unchanged (with a warning) when its decoded stream measures "
                 "below this many dB against it (default 60; 0: no floor)")
      ->check(CLI::Range(0.0, 300.0));
  app.add_option("--max-triangles", a.max_triangles,
                 "the triangle budget the output is decoded within: --psnr and --measure are of that decode, "
                 "and a .glb records it for loaders (default: a .glb primitive's own triangle count, so the "
                 "decoded asset is never heavier than its source; none for a .eqm stream; 0: none)")
      ->check(CLI::Range(int64_t{-1}, int64_t{1} << 40));
  app.add_option("--texture-size", a.texture_size,
                 ".glb output: side in texels of the atlas textures a textured primitive gets (default 0: "
                 "each input texture's own size)")
      ->check(CLI::Range(0, 16384));
  app.add_option("--threads", a.threads, "worker threads, 0 = all cores (the output does not depend on it)")
      ->check(CLI::Range(0, 256));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  SetWorkerThreadLimit(a.threads);
  if (IsSameFile(a.in_path, a.out_path)) return Fail(kName, a.out_path + ": is the input file; write the output elsewhere");
  if (a.base_vertices == 0) return Fail(kName, "--base-vertices must be positive or -1");
  if (EndsWith(a.out_path, ".gltf")) return Fail(kName, a.out_path + ": write .glb (binary glTF) or .eqm");
  if (EndsWith(a.out_path, ".glb") && EndsWith(a.in_path, ".srm")) {
    return Fail(kName, a.in_path + ": .glb output needs a mesh or glTF input (a .srm carries no scene)");
  }
  if (EndsWith(a.out_path, ".glb")) return EncodeToGlb(a);

  const bool srm_input = EndsWith(a.in_path, ".srm");
  auto source = srm_input ? ReadSemiRegularInput(a) : RemeshInput(a);
  if (!source.ok()) return Fail(kName, source.status().message());
  EncodeOptions options = ToEncodeOptions(a);
  if (source->original) {
    options.input_vertices = CountReferencedVertices(*source->original);
    options.original = &*source->original;
  }
  EncodeReport report;
  LevelCountReport search;
  options.progress = TerminalProgress(a.json);
  const auto encode_start = std::chrono::steady_clock::now();
  RepresentationReport choice;
  // An explicit --levels or --base-vertices asks for a normal mesh of that shape.
  RepresentationOptions representation;
  representation.allow_as_is = !srm_input && a.levels < 0 && a.base_vertices < 0;
  representation.repair = a.repair;
  if (representation.allow_as_is) representation.remesh = &source->remesh_options;
  auto bytes = EncodeChoosingRepresentation(source->remeshed, options, representation, &report, &search, &choice);
  ClearTerminalProgress(options.progress);
  if (!bytes.ok()) return Fail(kName, a.in_path + ": " + bytes.status().message());
  const double encode_seconds = SecondsSince(encode_start);
  const Status written = WriteFileAtomically(a.out_path, *bytes);
  if (!written.ok()) return Fail(kName, written.message());
  const RemeshReport& remesh_report = choice.walked_remesh ? *choice.walked_remesh : source->remesh;
  const double remesh_seconds = source->remesh_seconds;

  // Sizes jump between adjacent settings on small meshes; say so rather than
  // pretend the target was met.
  if (a.bpv > 0 && std::abs(report.bpv - a.bpv) > kBpvTolerance * a.bpv) {
    std::fprintf(stderr, "eqmesh encode: warning: nearest stream is %.3f bpv, %.1f %% from the %.3f bpv target\n",
                 report.bpv, 100.0 * std::abs(report.bpv - a.bpv) / a.bpv, a.bpv);
  }
  if (a.bpv > 0 && report.psnr_measured && report.psnr_db < kLowCeilingDb && source->original) {
    WarnOnLowCeiling(source->remeshed, *source->original);
  }
  if (a.json) {
    std::printf("%s\n",
                ToJson(a, remesh_report, report, search, choice, remesh_seconds, encode_seconds).dump(2).c_str());
  } else {
    const std::string as_is = choice.as_is_vertices < remesh_report.input_vertices
                                  ? "the input simplified to " + std::to_string(choice.as_is_vertices) +
                                        " vertices, coded as is"
                                  : std::string("the input coded as is");
    const std::string levels = std::to_string(report.level_bytes.size()) + " levels over a " +
                               std::to_string(choice.remeshed_base_vertices) + "-vertex base";
    const std::string shape = !choice.as_is              ? levels
                              : choice.remeshed_bytes > 0 ? as_is + " (" + std::to_string(choice.remeshed_bytes) +
                                                                " bytes as a normal mesh)"
                              : choice.nothing_remeshed   ? as_is + " (too small to remesh)"
                                                          : as_is + " (no normal-mesh stream met the target)";
    std::printf("%s: %zu bytes, %.3f bits per input vertex (%zu vertices), %s", a.out_path.c_str(),
                report.total_bytes, report.bpv, options.input_vertices, shape.c_str());
    if (report.psnr_measured) std::printf(", PSNR %.2f dB", report.psnr_db);
    std::printf("\n");
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("encode", "encode a mesh into an eqmesh stream (.eqm) or a compressed .glb", RunEncode);

}  // namespace eqmesh::cli

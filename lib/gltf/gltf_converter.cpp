#include "gltf/gltf_converter.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "coding/decoder.h"
#include "coding/level_count_search.h"
#include "coding/representation_choice.h"
#include "gltf/accessor_io.h"
#include "gltf/gltf_io.h"
#include "gltf/stream_decoder.h"
#include "gltf/textured_compression.h"
#include "mesh/repair.h"
#include "mesh_io/file_bytes.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh::gltf {
namespace {

bool EndsWith(std::string s, const std::string& suffix) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (s.size() >= 3 && s.compare(s.size() - 3, 3, ".gz") == 0) s.resize(s.size() - 3);
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool IsGltfFile(const std::string& path) {
  if (EndsWith(path, ".gltf") || EndsWith(path, ".glb")) return true;
  auto bytes = ReadFileBytes(path, 64u << 20);  // sniff only when the name says nothing
  return bytes.ok() && bytes->size() >= 4 && std::memcmp(bytes->data(), "glTF", 4) == 0;
}

StatusOr<CompressedGeometry> CompressWithEqmesh(const ConvertOptions& options, const PrimitiveGeometry& primitive) {
  const bool textured = !primitive.textures.empty();
  // UV seams split a textured primitive's positions; welded (as Remesh() would),
  // its vertex count is the surface's. Only where the weld keeps it manifold:
  // parts that merely touch stay apart.
  const Mesh welded = textured ? WeldSeams(primitive.mesh) : Mesh();
  const Mesh& mesh = textured ? welded : primitive.mesh;
  RemeshReport remesh_report;
  RemeshOptions remesh = options.remesh;
  // The floor the stream must meet, as a floor for the remesh (plus coding's margin).
  const double floor = std::max(options.min_psnr, options.codec.target_psnr);
  if (floor > 0) remesh.min_psnr = std::max(remesh.min_psnr, floor + kRemeshMarginDb);
  EQMESH_ASSIGN_OR_RETURN(const SemiRegularMesh remeshed, Remesh(mesh, remesh, &remesh_report));
  EncodeOptions codec = options.codec;
  codec.input_vertices = CountReferencedVertices(mesh);
  codec.original = &mesh;
  // Textured primitives are decoded whole: atlas seams are split per uniform level,
  // which an adaptive cut does not follow.
  const uint64_t budget = textured                   ? 0
                          : options.max_triangles < 0 ? primitive.mesh.faces.size()
                                                      : static_cast<uint64_t>(options.max_triangles);
  // A rate or PSNR target measures the stream it chooses (as `encode x.eqm`
  // reports it); a bare lambda needs a measurement of its own for the floor.
  const bool targeted = codec.target_bpv > 0 || codec.target_psnr > 0;
  if (options.min_psnr > 0 && !targeted) codec.measure_psnr = true;
  EncodeReport encode_report;
  CompressedGeometry out;
  codec.max_triangles = budget;
  // The input coded as is competes where the user left the remesh's shape open;
  // not for textured primitives, whose atlas has a cell per base face.
  RepresentationOptions representation;
  representation.allow_as_is = !textured && remesh.levels < 0 && remesh.base_vertices < 0;
  representation.repair = remesh.repair;
  representation.floor_db = options.min_psnr;
  if (representation.allow_as_is) representation.remesh = &remesh;
  RepresentationReport choice;
  auto stream = EncodeChoosingRepresentation(remeshed, codec, representation, &encode_report, nullptr, &choice);
  const bool floor_missed = stream.ok() && options.min_psnr > 0 && encode_report.psnr_db < options.min_psnr;
  if (budget > 0 && options.max_triangles < 0 &&
      (floor_missed || (!stream.ok() && stream.status().code() == StatusCode::kTargetOutOfReach))) {
    // The source's own triangle count cannot carry the quality asked for: decode
    // whole rather than ship it broken, and say so.
    char text[160];
    std::snprintf(text, sizeof(text), "decoded whole, beyond its %llu triangles: within them ",
                  static_cast<unsigned long long>(budget));
    out.note = text;
    if (stream.ok()) {
      std::snprintf(text, sizeof(text), "it measures %.2f dB, below the %.2f dB floor", encode_report.psnr_db,
                    options.min_psnr);
      out.note += text;
    } else {
      out.note += stream.status().message();
    }
    codec.max_triangles = 0;
    encode_report = EncodeReport();
    stream = EncodeChoosingRepresentation(remeshed, codec, representation, &encode_report, nullptr, &choice);
  }
  if (!stream.ok()) return stream.status();
  out.stream = std::move(stream).value();
  out.as_is = choice.as_is;
  out.triangle_budget = codec.max_triangles;
  if (options.min_psnr > 0 && encode_report.psnr_db < options.min_psnr) {
    EQMESH_ASSIGN_OR_RETURN(const double ceiling, RemeshCeilingPsnr(remeshed, mesh));
    char text[200];
    std::snprintf(text, sizeof(text), "decoded PSNR %.2f dB is below the %.2f dB floor (--min-psnr; the remesh "
                  "itself measures %.2f dB)", encode_report.psnr_db, options.min_psnr, ceiling);
    return Status(StatusCode::kTargetOutOfReach, text);
  }
  out.psnr_db = encode_report.psnr_measured ? encode_report.psnr_db : 0.0;
  if (textured) {
    EQMESH_RETURN_IF_ERROR(AddAtlasAndTextures(primitive, options.texture_size, &out));
    return out;
  }
  EQMESH_ASSIGN_OR_RETURN(out.chunk_lengths, EqmeshStreamLayout()(out.stream.data(), out.stream.size()));
  // Placeholder counts and bounds come from the decoded data (spec rule 6).
  EQMESH_ASSIGN_OR_RETURN(out.decoded, Decode(out.stream.data(), out.stream.size()));
  if (out.triangle_budget > 0 && out.decoded.faces.size() > out.triangle_budget) {
    DecodeOptions within;
    within.max_triangles = out.triangle_budget;
    EQMESH_ASSIGN_OR_RETURN(out.loaded, Decode(out.stream.data(), out.stream.size(), within));
  }
  return out;
}

StatusOr<uint64_t> WriteOutput(const tinygltf::Model& model, const std::string& path) {
  EQMESH_RETURN_IF_ERROR(WriteGlb(model, path));
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return IoError(path + ": " + ec.message());
  return static_cast<uint64_t>(size);
}

// See ConvertOptions::strict.
Status CheckFailures(const ConvertReport& report, const ConvertOptions& options) {
  for (const PrimitiveOutcome& p : report.primitives) {
    if (!p.failure.ok() && (options.strict || report.compressed == 0)) return p.failure;
  }
  return Status::Ok();
}

}  // namespace

GeometryCompressor MakeEqmeshCompressor(const ConvertOptions& options) {
  return [options](const PrimitiveGeometry& primitive, const std::string& label) -> StatusOr<CompressedGeometry> {
    auto out = CompressWithEqmesh(options, primitive);
    if (!out.ok()) return out.status().WithContext(label);
    return out;
  };
}

StatusOr<ConvertReport> ConvertModel(tinygltf::Model* model, const ConvertOptions& options) {
  ConvertReport report;
  const ContainerOptions container{options.fallback, options.drop_other_attributes};
  EQMESH_RETURN_IF_ERROR(CompressPrimitives(model, MakeEqmeshCompressor(options), container, &report));
  return report;
}

StatusOr<ConvertReport> ConvertToCompressedGltf(tinygltf::Model model, const std::string& output_path,
                                                const ConvertOptions& options) {
  EQMESH_ASSIGN_OR_RETURN(ConvertReport report, ConvertModel(&model, options));
  EQMESH_RETURN_IF_ERROR(CheckFailures(report, options));
  EQMESH_ASSIGN_OR_RETURN(report.output_bytes, WriteOutput(model, output_path));
  return report;
}

StatusOr<ConvertReport> ConvertToCompressedGltf(const std::string& input_path, const std::string& output_path,
                                                const ConvertOptions& options) {
  tinygltf::Model model;
  if (IsGltfFile(input_path)) {
    EQMESH_ASSIGN_OR_RETURN(model, ReadGltfModel(input_path));
  } else {
    EQMESH_ASSIGN_OR_RETURN(const Mesh mesh, ReadMesh(input_path));
    EQMESH_ASSIGN_OR_RETURN(model, ModelFromMesh(mesh));
  }
  auto report = ConvertModel(&model, options);
  if (!report.ok()) return report.status().WithContext(input_path);
  EQMESH_RETURN_IF_ERROR(CheckFailures(*report, options).WithContext(input_path));
  std::error_code ec;
  report->input_bytes = static_cast<uint64_t>(std::filesystem::file_size(input_path, ec));
  EQMESH_ASSIGN_OR_RETURN(report->output_bytes, WriteOutput(model, output_path));
  return report;
}

}  // namespace eqmesh::gltf

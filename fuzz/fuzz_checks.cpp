// Checks behind the fuzz targets and the fuzz regression test (fuzz_checks.h).
#include "fuzz/fuzz_checks.h"

#include <cstring>
#include <vector>

#include "coding/decoder.h"
#include "gltf/extension.h"
#include "gltf/gltf_loader.h"
#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::fuzz {
namespace {

// A clean rejection: a real error code (kInternal means our own invariant broke)
// and a one-line message.
std::string CheckRejection(const Status& status) {
  if (status.ok()) return "an OK status where an error was expected";
  if (status.code() == StatusCode::kInternal) return "internal error on input: " + status.message();
  if (status.message().empty()) return "error without a message";
  if (status.message().find('\n') != std::string::npos) return "multi-line error: " + status.message();
  return "";
}

std::string CheckMesh(const Mesh& mesh, uint64_t max_vertices, uint64_t max_faces) {
  if (mesh.positions.size() > max_vertices || mesh.faces.size() > max_faces) {
    return std::to_string(mesh.positions.size()) + " vertices / " + std::to_string(mesh.faces.size()) +
           " faces exceed the bound " + std::to_string(max_vertices) + " / " + std::to_string(max_faces);
  }
  for (const Vec3& p : mesh.positions) {
    if (!p.allFinite()) return "non-finite coordinate in the output";
  }
  for (const Face& f : mesh.faces) {
    for (const uint32_t i : f) {
      if (i >= mesh.positions.size()) return "face index out of range in the output";
    }
  }
  return "";
}

// What a successful decode must agree with: the header ReadStreamInfo parses and
// the options it was given.
std::string CheckDecodeInfo(const uint8_t* stream, size_t size, const DecodeOptions& options,
                            const DecodeInfo& info) {
  auto parsed = ReadStreamInfo(stream, size);
  if (!parsed.ok()) return "Decode succeeded where ReadStreamInfo fails: " + parsed.status().message();
  const StreamInfo& s = *parsed;
  if (s.prefix_size.size() != static_cast<size_t>(s.levels) + 1 || s.total_size != s.prefix_size.back()) {
    return "inconsistent StreamInfo prefix sizes";
  }
  if (info.levels_in_stream != s.levels || info.levels_decoded < 0 || info.levels_decoded > s.levels) {
    return "levels_decoded " + std::to_string(info.levels_decoded) + " outside the stream's " +
           std::to_string(s.levels);
  }
  if (options.max_level >= 0 && info.levels_decoded > options.max_level) return "decoded beyond max_level";
  if (size > s.total_size) return "trailing bytes accepted";
  if (!options.allow_truncated) {
    if (size != s.total_size) return "truncated stream accepted without allow_truncated";
    const int expected = options.max_level < 0 ? s.levels : std::min(options.max_level, s.levels);
    if (info.levels_decoded != expected) return "complete stream decoded to the wrong level";
  }
  if (info.truncated != (size < s.total_size)) return "DecodeInfo::truncated is wrong";
  return "";
}

}  // namespace

int MaxLevelFromControl(uint8_t control) {
  const int level = control & 0x0F;
  return level > bitstream::kMaxLevels ? -1 : level;
}

std::string CheckStreamDecoder(const uint8_t* data, size_t size) {
  if (size == 0) return "";
  const uint8_t control = data[0];
  const uint8_t* stream = data + 1;
  const size_t n = size - 1;
  DecodeOptions options;
  options.max_level = MaxLevelFromControl(control);
  options.allow_truncated = (control & kControlAllowTruncated) != 0;
  DecodeInfo info;
  // Finest level and kept components together stay below these (bitstream limits).
  const uint64_t max_faces = 2 * bitstream::kMaxFinestFaces;
  const uint64_t max_vertices = 3 * max_faces;
  if ((control & kControlSemiRegular) != 0) {
    auto mesh = DecodeSemiRegular(stream, n, options, &info);
    if (!mesh.ok()) return CheckRejection(mesh.status());
    const SemiRegularHierarchy& h = mesh->hierarchy;
    if (h.levels() != info.levels_decoded) return "hierarchy built to a level other than levels_decoded";
    if (mesh->positions.size() != h.NumVertices(h.levels())) return "position count differs from the hierarchy";
    Mesh level;
    level.positions = mesh->positions;
    level.faces = h.Faces(h.levels());
    std::string problem = CheckMesh(level, max_vertices, max_faces);
    if (problem.empty()) problem = CheckMesh(mesh->kept_exactly, max_vertices, max_faces);
    if (problem.empty()) problem = CheckDecodeInfo(stream, n, options, info);
    return problem;
  }
  auto mesh = Decode(stream, n, options, &info);
  if (!mesh.ok()) {
    (void)ReadStreamInfo(stream, n);  // the header parser on its own
    return CheckRejection(mesh.status());
  }
  std::string problem = CheckMesh(*mesh, max_vertices, max_faces);
  if (problem.empty()) problem = CheckDecodeInfo(stream, n, options, info);
  return problem;
}

std::string CheckGltfLoader(const uint8_t* data, size_t size) {
  if (size == 0) return "";
  gltf::LoadOptions options;
  options.max_level = MaxLevelFromControl(data[0]);
  const std::vector<uint8_t> bytes(data + 1, data + size);
  gltf::LoadReport report;
  auto model = gltf::LoadGltfFromBytes(bytes, "fuzz.glb", options, &report);
  if (!model.ok()) return CheckRejection(model.status());
  for (const tinygltf::Mesh& m : model->meshes) {
    for (const tinygltf::Primitive& p : m.primitives) {
      if (p.extensions.count(gltf::kExtensionName) != 0) return "a compressed primitive survived loading";
    }
  }
  for (const gltf::PrimitiveLoad& load : report.decoded) {
    if (options.max_level >= 0 && load.level_decoded > options.max_level) return "loader decoded beyond max_level";
    if (load.stream_bytes_read > bytes.size()) return "loader read more stream bytes than the file holds";
  }
  auto flat = gltf::FlattenToMesh(*model);
  if (!flat.ok()) return CheckRejection(flat.status());
  // Decoded streams may expand (bitstream limits), instancing multiplies.
  const uint64_t bound = 64 * static_cast<uint64_t>(size) + 4 * bitstream::kMaxFinestFaces;
  return CheckMesh(*flat, bound, bound);
}

std::string CheckMeshReader(const char* format, const uint8_t* data, size_t size) {
  ReadReport report;
  StatusOr<Mesh> mesh = ParseError("unknown format");
  if (std::strcmp(format, "obj") == 0) {
    mesh = io_internal::ReadObj(data, size, "fuzz.obj", &report);
  } else if (std::strcmp(format, "ply") == 0) {
    mesh = io_internal::ReadPly(data, size, "fuzz.ply", &report);
  } else if (std::strcmp(format, "off") == 0) {
    mesh = io_internal::ReadOff(data, size, "fuzz.off", &report);
  } else {
    return std::string("unknown reader ") + format;
  }
  if (!mesh.ok()) return CheckRejection(mesh.status());
  if (mesh->faces.empty()) return "a mesh without faces was accepted";
  // mesh_io.h: the output is bounded by a small multiple of the input. Every
  // triangle costs at least one byte (a binary PLY int8 corner), every vertex at
  // least three (int8 x, y, z).
  return CheckMesh(*mesh, size / 3 + 1, size + 1);
}

}  // namespace eqmesh::fuzz

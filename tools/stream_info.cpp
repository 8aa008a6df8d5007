// eqmesh info on a stream: see stream_info.h.
#include "tools/stream_info.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "coding/bitstream_shared.h"
#include "coding/decoder.h"
#include "mesh_io/file_bytes.h"
#include "tools/command.h"

namespace eqmesh::cli {
namespace {

constexpr const char* kName = "info";

struct LevelCounts {
  uint64_t vertices = 0, faces = 0, edges = 0;
};

// Counts of levels 0..levels from the base mesh: 1-to-4 subdivision adds a
// vertex per edge, splits each edge in two and adds three edges per face. The
// base's edge count is its first refinement's odd-vertex count (ext_spec B.1),
// from one Refine of the base alone.
StatusOr<std::vector<LevelCounts>> CountLevels(const SemiRegularMesh& base, int levels) {
  std::vector<LevelCounts> counts(1);
  counts[0] = {base.hierarchy.NumVertices(0), base.hierarchy.BaseFaces().size(), 0};
  if (levels == 0) return counts;
  SemiRegularHierarchy once = base.hierarchy;
  EQMESH_RETURN_IF_ERROR(once.Refine());
  counts[0].edges = once.NumOddVertices(0);
  for (int k = 0; k < levels; ++k) {
    const LevelCounts& c = counts.back();
    counts.push_back({c.vertices + c.edges, 4 * c.faces, 2 * c.edges + 3 * c.faces});
  }
  return counts;
}

const char* TransformName(bitstream::TransformId t) {
  return t == bitstream::TransformId::kLifted ? "lifted" : "unlifted";
}

const char* CoderName(bitstream::CoderId c) {
  switch (c) {
    case bitstream::CoderId::kEq: return "eq";
    case bitstream::CoderId::kZerotree: return "zerotree";
    case bitstream::CoderId::kUniform: return "uniform";
  }
  return "unknown";
}

struct Report {
  std::string path;
  StreamInfo stream;
  uint64_t bytes = 0;
  std::vector<LevelCounts> levels;  // empty when the base chunk is not in the file
  uint64_t kept_vertices = 0, kept_faces = 0;
};

nlohmann::json ToJson(const Report& r) {
  const StreamInfo& s = r.stream;
  nlohmann::json j;
  j["file"] = r.path;
  j["format"] = "eqm";
  j["bytes"] = r.bytes;
  j["version"] = std::to_string(s.version_major) + "." + std::to_string(s.version_minor);
  j["transform"] = TransformName(s.transform);
  j["coder"] = CoderName(s.coder);
  j["levels"] = s.levels;
  j["kept_exactly"] = s.has_kept_exactly;
  j["compact_base"] = s.has_compact_base;
  j["compact_kept"] = s.has_compact_kept;
  j["tangential_context"] = s.has_tangential_context;
  j["lambda"] = s.lambda;
  j["tangential_factor"] = s.tangential_factor;
  j["quantum"] = s.quantum;
  j["header_bytes"] = s.header_size;
  j["base_bytes"] = s.base_size;
  j["kept_bytes"] = s.kept_size;
  j["crease_bytes"] = s.crease_size;
  j["level_offsets"] = s.level_offsets;
  j["level_sizes"] = s.level_sizes;
  j["prefix_sizes"] = s.prefix_size;
  j["stream_bytes"] = s.total_size;
  j["truncated"] = r.bytes < s.total_size;
  nlohmann::json levels = nlohmann::json::array();
  for (size_t k = 0; k < r.levels.size(); ++k) {
    levels.push_back({{"level", k},
                      {"vertices", r.levels[k].vertices + r.kept_vertices},
                      {"faces", r.levels[k].faces + r.kept_faces},
                      {"prefix_bytes", s.prefix_size[k]}});
  }
  j["level_meshes"] = levels;
  return j;
}

void PrintTable(const Report& r) {
  const StreamInfo& s = r.stream;
  auto row = [](const char* key, const std::string& value) { std::printf("%-24s %s\n", key, value.c_str()); };
  auto num = [](uint64_t n) { return std::to_string(n); };
  char buf[128];
  row("file", r.path);
  row("format", "eqm stream " + num(s.version_major) + "." + num(s.version_minor));
  row("bytes", num(r.bytes) + (r.bytes < s.total_size ? " (truncated: the stream has " + num(s.total_size) + ")" : ""));
  row("transform", TransformName(s.transform));
  row("coder", CoderName(s.coder));
  row("levels", num(static_cast<uint64_t>(s.levels)));
  std::string flags = s.has_compact_base ? "compact base" : "Draco base";
  if (s.has_tangential_context) flags += ", tangential context";
  if (s.has_kept_exactly) flags += s.has_compact_kept ? ", compact kept-exactly chunk" : ", Draco kept-exactly chunk";
  if (s.has_creases) flags += ", crease chunk (" + num(s.crease_size) + " bytes)";
  row("chunks", flags);
  std::snprintf(buf, sizeof buf, "%.6g (tangential factor %.6g), quantum %.6g", s.lambda, s.tangential_factor,
                s.quantum);
  row("lambda", buf);
  row("header / base / kept", num(s.header_size) + " / " + num(s.base_size) + " / " + num(s.kept_size) + " bytes");
  for (size_t k = 0; k < s.prefix_size.size(); ++k) {
    std::string line = "prefix " + num(s.prefix_size[k]) + " bytes";
    if (k > 0) line += " (chunk " + num(s.level_sizes[k - 1]) + ")";
    if (k < r.levels.size()) {
      line += ": " + num(r.levels[k].vertices + r.kept_vertices) + " vertices, " +
              num(r.levels[k].faces + r.kept_faces) + " faces";
    }
    std::snprintf(buf, sizeof buf, "level %zu", k);
    row(buf, line);
  }
}

}  // namespace

bool LooksLikeStream(const std::string& path) {
  if (EndsWith(path, ".eqm")) return true;
  std::ifstream file(path, std::ios::binary);
  char magic[sizeof bitstream::kMagic] = {};
  return file.read(magic, sizeof magic) && std::memcmp(magic, bitstream::kMagic, sizeof magic) == 0;
}

int PrintStreamInfo(const std::string& path, bool json) {
  auto bytes = ReadFileBytes(path, kMaxStreamFileBytes);
  if (!bytes.ok()) return Fail(kName, bytes.status().message());
  auto stream = ReadStreamInfo(bytes->data(), bytes->size());
  if (!stream.ok()) return Fail(kName, path + ": " + stream.status().message());
  Report r;
  r.path = path;
  r.stream = *stream;
  r.bytes = bytes->size();
  // Level counts need the base chunk; a prefix without it still gets the header.
  if (r.bytes >= r.stream.prefix_size[0]) {
    DecodeOptions options;
    options.max_level = 0;
    options.allow_truncated = true;
    auto base = DecodeSemiRegular(bytes->data(), bytes->size(), options);
    if (!base.ok()) return Fail(kName, path + ": " + base.status().message());
    auto levels = CountLevels(*base, r.stream.levels);
    if (!levels.ok()) return Fail(kName, path + ": " + levels.status().message());
    r.levels = std::move(*levels);
    r.kept_vertices = base->kept_exactly.positions.size();
    r.kept_faces = base->kept_exactly.faces.size();
  }
  if (json) {
    std::printf("%s\n", ToJson(r).dump(2).c_str());
  } else {
    PrintTable(r);
  }
  return 0;
}

}  // namespace eqmesh::cli

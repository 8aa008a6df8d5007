// eqmesh decode IN.(eqm|glb|gltf) OUT.(ply|obj|off|glb): stream or compressed glTF ->
// plain mesh / plain glTF at any level.
#include <chrono>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "coding/decoder.h"
#include "gltf/gltf_loader.h"
#include "mesh_io/file_bytes.h"
#include "mesh_io/mesh_io.h"
#include "tools/command.h"

namespace eqmesh::cli {
namespace {

constexpr const char* kName = "decode";

// Compressed glTF in: decode every EXT_normal_mesh_compression primitive. A .glb
// output keeps the whole scene as plain glTF; OBJ/PLY/OFF get the flattened geometry.
int DecodeGltf(const std::string& in_path, const std::string& out_path, int level, int64_t max_triangles,
               bool json) {
  gltf::LoadOptions options;
  options.max_level = level;
  options.max_triangles = max_triangles;
  const auto start = std::chrono::steady_clock::now();
  auto model = gltf::LoadGltf(in_path, options);
  if (!model.ok()) return Fail(kName, model.status().message());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto flat = gltf::FlattenToMesh(*model);
  if (!flat.ok()) return Fail(kName, in_path + ": " + flat.status().message());
  const Status written =
      EndsWith(out_path, ".glb") ? gltf::WriteDecodedGlb(*model, out_path) : WriteMesh(*flat, out_path);
  if (!written.ok()) return Fail(kName, written.message());
  if (json) {
    nlohmann::json j;
    j["input"] = in_path;
    j["output"] = out_path;
    j["vertices"] = flat->positions.size();
    j["faces"] = flat->faces.size();
    j["decode_seconds"] = seconds;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s: %zu vertices, %zu faces\n", out_path.c_str(), flat->positions.size(), flat->faces.size());
  }
  return 0;
}

int RunDecode(int argc, char** argv) {
  CLI::App app{"Decode an eqmesh stream (.eqm) or a glTF with EXT_normal_mesh_compression (.glb) to a mesh", argv[0]};
  std::string in_path, out_path;
  int level = -1;
  int64_t max_triangles = -1;
  bool json = false, allow_truncated = false;
  app.add_option("IN", in_path, "eqmesh stream (.eqm) or glTF with EXT_normal_mesh_compression (.glb .gltf)")->required();
  app.add_option("OUT", out_path, "output mesh (.ply .obj .off .glb)")->required();
  app.add_option("--level", level, "decode up to this level (-1: all)")->check(CLI::Range(-1, 64));
  app.add_option("--max-triangles", max_triangles,
                 "at most this many triangles: faces are refined where the surface needs them, not level by "
                 "level, and closed without cracks. 0: every triangle of the decoded levels; default: a .glb's "
                 "recorded budget (its source's triangle count), none for a .eqm stream")
      ->check(CLI::Range(int64_t{-1}, int64_t{1} << 40));
  app.add_flag("--allow-truncated", allow_truncated,
               "decode the complete levels of a truncated stream instead of failing");
  app.add_flag("--json", json, "print one JSON object with the decode report");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (IsSameFile(in_path, out_path)) return Fail(kName, out_path + ": is the input file; write the output elsewhere");
  if (EndsWith(in_path, ".glb") || EndsWith(in_path, ".gltf")) {
    return DecodeGltf(in_path, out_path, level, max_triangles, json);
  }
  auto bytes = ReadFileBytes(in_path, kMaxStreamFileBytes);
  if (!bytes.ok()) return Fail(kName, bytes.status().message());
  const auto start = std::chrono::steady_clock::now();
  DecodeOptions options;
  options.max_level = level;
  options.allow_truncated = allow_truncated;
  options.max_triangles = max_triangles < 0 ? 0 : static_cast<uint64_t>(max_triangles);
  DecodeInfo info;
  auto mesh = Decode(bytes->data(), bytes->size(), options, &info);
  if (!mesh.ok()) return Fail(kName, in_path + ": " + mesh.status().message());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Status written = WriteMesh(*mesh, out_path);
  if (!written.ok()) return Fail(kName, written.message());
  if (level > info.levels_in_stream) {
    std::fprintf(stderr, "eqmesh decode: note: the stream has %d levels; decoded all of them\n",
                 info.levels_in_stream);
  }
  if (json) {
    nlohmann::json j;
    j["input"] = in_path;
    j["output"] = out_path;
    j["bytes"] = bytes->size();
    j["levels_in_stream"] = info.levels_in_stream;
    j["levels_decoded"] = info.levels_decoded;
    j["truncated"] = info.truncated;
    j["vertices"] = mesh->positions.size();
    j["faces"] = mesh->faces.size();
    j["level_offsets"] = info.stream.level_offsets;
    j["level_sizes"] = info.stream.level_sizes;
    j["decode_seconds"] = seconds;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s: level %d of %d, %zu vertices, %zu faces\n", out_path.c_str(),
                info.levels_decoded, info.levels_in_stream, mesh->positions.size(),
                mesh->faces.size());
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("decode", "decode an eqmesh stream (.eqm) or compressed .glb to a plain mesh / glTF", RunDecode);

}  // namespace eqmesh::cli

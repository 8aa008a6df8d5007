// eqmesh info FILE [--json]: reads a mesh and prints its diagnosis (counts,
// boundary, manifoldness, orientation, components, genus, degeneracy); for an
// eqmesh stream, what the stream holds (stream_info.h).
#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mesh/diagnose.h"
#include "mesh/triangle_bvh.h"
#include "mesh_io/mesh_io.h"
#include "metrics/self_crossings.h"
#include "tools/command.h"
#include "tools/gltf_info.h"
#include "tools/stream_info.h"

namespace eqmesh::cli {
namespace {

struct InfoResult {
  std::string path;
  ReadReport read;
  std::vector<GltfPrimitiveInfo> primitives;  // glTF with EXT_normal_mesh_compression
  MeshDiagnosis diagnosis;
  size_t self_crossing_faces = 0;  // faces with an edge through another face
  double read_seconds = 0.0;
  double diagnose_seconds = 0.0;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// -1 (undefined genus) becomes null rather than a number someone might sum.
nlohmann::json GenusArray(const std::vector<int64_t>& genus) {
  nlohmann::json out = nlohmann::json::array();
  for (int64_t g : genus) out.push_back(g >= 0 ? nlohmann::json(g) : nlohmann::json(nullptr));
  return out;
}

nlohmann::json PrimitivesJson(const std::vector<GltfPrimitiveInfo>& primitives) {
  nlohmann::json out = nlohmann::json::array();
  for (const GltfPrimitiveInfo& p : primitives) {
    nlohmann::json j = {{"mesh", p.mesh}, {"primitive", p.primitive}, {"compressed", p.compressed},
                        {"vertices", p.vertices}, {"triangles", p.triangles}};
    if (p.compressed) {
      j["stream_bytes"] = p.stream_bytes;
      j["levels"] = p.levels;
      j["coder"] = p.coder;
      j["prefix_bytes"] = p.prefix_bytes;
    }
    out.push_back(j);
  }
  return out;
}

nlohmann::json ToJson(const InfoResult& r) {
  const MeshDiagnosis& d = r.diagnosis;
  nlohmann::json j;
  j["file"] = r.path;
  j["format"] = r.read.format;
  j["vertices"] = d.vertices + r.read.dropped_unreferenced_vertices;  // as stored in the file
  j["referenced_vertices"] = d.referenced_vertices;
  j["dropped_unreferenced_vertices"] = r.read.dropped_unreferenced_vertices;
  j["faces"] = d.faces;
  j["edges"] = d.edges;
  j["boundary_edges"] = d.boundary_edges;
  j["boundary_loops"] = d.boundary_loops;
  j["non_manifold_edges"] = d.non_manifold_edges;
  j["non_manifold_vertices"] = d.non_manifold_vertices;
  j["inconsistent_edges"] = d.inconsistent_edges;
  j["components"] = d.components;
  j["closed_components"] = d.closed_components;
  j["vertex_connected_components"] = d.vertex_connected_components;
  j["genus"] = GenusArray(d.closed_genus);
  j["degenerate_faces"] = d.degenerate_faces;
  j["duplicate_positions"] = d.duplicate_positions;
  j["self_crossing_faces"] = r.self_crossing_faces;
  j["bbox_diagonal"] = d.bbox_diagonal;
  j["manifold"] = d.IsManifold();
  j["polygons_triangulated"] = r.read.polygons_triangulated;
  j["notes"] = r.read.notes;
  if (!r.primitives.empty()) j["primitives"] = PrimitivesJson(r.primitives);
  j["read_seconds"] = r.read_seconds;
  j["diagnose_seconds"] = r.diagnose_seconds;
  j["seconds"] = r.read_seconds + r.diagnose_seconds;
  return j;
}

// A glTF with EXT_normal_mesh_compression: its primitives, then the geometry
// every level of every stream decodes to.
StatusOr<Mesh> ReadDecodedGltf(const std::string& path, InfoResult* result) {
  EQMESH_ASSIGN_OR_RETURN(CompressedGltf gltf, ReadCompressedGltf(path));
  result->read.format = "gltf (EXT_normal_mesh_compression)";
  result->primitives = std::move(gltf.primitives);
  return std::move(gltf.decoded);
}

// "0 (x150), 1 (x1), undefined (x2)": readable even for hundreds of components.
std::string GenusSummary(const std::vector<int64_t>& genus) {
  if (genus.empty()) return "-";
  std::map<int64_t, size_t> histogram;
  for (int64_t g : genus) ++histogram[g];
  std::ostringstream s;
  bool first = true;
  for (const auto& [g, count] : histogram) {
    s << (first ? "" : ", ") << (g >= 0 ? std::to_string(g) : std::string("undefined"));
    if (genus.size() > 1) s << " (x" << count << ")";
    first = false;
  }
  return s.str();
}

void PrintTable(const InfoResult& r) {
  const MeshDiagnosis& d = r.diagnosis;
  auto row = [](const char* key, const std::string& value) { std::printf("%-24s %s\n", key, value.c_str()); };
  auto num = [](size_t n) { return std::to_string(n); };
  row("file", r.path);
  row("format", r.read.format);
  row("vertices", num(d.vertices + r.read.dropped_unreferenced_vertices) + " stored, " +
                      num(d.referenced_vertices) + " referenced, " +
                      num(r.read.dropped_unreferenced_vertices) + " unreferenced dropped");
  row("faces", num(d.faces) + (r.read.polygons_triangulated
                                   ? " (" + num(r.read.polygons_triangulated) + " polygons triangulated)"
                                   : std::string()));
  row("edges", num(d.edges));
  row("boundary", num(d.boundary_edges) + " edges in " + num(d.boundary_loops) + " loops");
  row("non-manifold edges", num(d.non_manifold_edges));
  row("non-manifold vertices", num(d.non_manifold_vertices));
  row("inconsistent edges", num(d.inconsistent_edges));
  row("components", num(d.components) + " (" + num(d.closed_components) + " closed; " +
                        num(d.vertex_connected_components) + " when touching at a vertex counts)");
  row("genus (closed comps.)", GenusSummary(d.closed_genus));
  row("degenerate faces", num(d.degenerate_faces));
  row("duplicate positions", num(d.duplicate_positions));
  row("self-crossing faces", num(r.self_crossing_faces) + " (an edge through another face: the surface passes "
                                                          "through itself)");
  char diag[64];
  std::snprintf(diag, sizeof(diag), "%.6g", d.bbox_diagonal);
  row("bbox diagonal", diag);
  row("manifold", d.IsManifold() ? "yes" : "no");
  for (const GltfPrimitiveInfo& p : r.primitives) {
    const std::string name = "mesh " + num(static_cast<size_t>(p.mesh)) + " prim " + num(static_cast<size_t>(p.primitive));
    std::string value = num(p.vertices) + " vertices, " + num(p.triangles) + " triangles";
    if (p.compressed) {
      value += " decoded from a " + num(p.stream_bytes) + "-byte " + p.coder + " stream of " +
               num(static_cast<size_t>(p.levels)) + " levels; bytes to level 0.." + num(static_cast<size_t>(p.levels)) + ":";
      for (uint64_t b : p.prefix_bytes) value += " " + num(b);
    } else {
      value += ", not compressed";
    }
    row(name.c_str(), value);
  }
  for (const std::string& note : r.read.notes) row("note", note);
  char secs[64];
  std::snprintf(secs, sizeof(secs), "%.3f (read %.3f, diagnose %.3f)", r.read_seconds + r.diagnose_seconds,
                r.read_seconds, r.diagnose_seconds);
  row("seconds", secs);
}

int RunInfo(int argc, char** argv) {
  CLI::App app{"Print the topology and geometry diagnosis of a mesh, or what an eqmesh stream or compressed glTF holds."};
  std::string path;
  bool json = false;
  app.add_option("file", path,
                 "mesh file: .obj .ply .off .gltf .glb, optionally gzip-compressed; a glTF written by "
                 "`eqmesh encode` (its primitives, each stream's levels and byte prefixes, and the decoded "
                 "geometry); or an eqmesh stream (.eqm: header, chunk sizes and the vertex count of every "
                 "level, nothing decoded past the base)")
      ->required();
  app.add_flag("--json", json, "print one JSON object instead of a table");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (LooksLikeStream(path)) return PrintStreamInfo(path, json);
  InfoResult result;
  result.path = path;
  const auto start = std::chrono::steady_clock::now();
  StatusOr<Mesh> mesh = IsCompressedGltf(path) ? ReadDecodedGltf(path, &result) : ReadMesh(path, &result.read);
  if (!mesh.ok()) {
    const std::string& message = mesh.status().message();
    return Fail("info", message.find(path) == std::string::npos ? path + ": " + message : message);
  }
  result.read_seconds = SecondsSince(start);
  const auto diagnose_start = std::chrono::steady_clock::now();
  result.diagnosis = Diagnose(*mesh);
  if (StatusOr<TriangleBvh> bvh = TriangleBvh::Build(*mesh); bvh.ok()) {
    result.self_crossing_faces = CountSelfCrossingFaces(*mesh, *bvh);
  }
  result.diagnose_seconds = SecondsSince(diagnose_start);
  if (json) {
    std::printf("%s\n", ToJson(result).dump(2).c_str());
  } else {
    PrintTable(result);
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("info", "print a mesh's topology and geometry diagnosis, or an eqmesh stream's contents", RunInfo);

}  // namespace eqmesh::cli

// eqmesh convert IN OUT: reads any supported mesh (OBJ, PLY incl. tristrips, OFF,
// glTF/GLB, gzip) and writes it in the normal form every stage sees (unreferenced
// vertices dropped, polygons triangulated). The benchmark uses it to hand every
// peer codec the same positions-and-connectivity-only input.
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mesh_io/mesh_io.h"
#include "mesh_io/semi_regular_io.h"
#include "tools/command.h"
#include "tools/gltf_info.h"

namespace eqmesh::cli {
namespace {

StatusOr<Mesh> ReadFinestLevel(const std::string& path) {
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh m, ReadSemiRegular(path));
  return ExtractLevel(m, m.hierarchy.levels());
}

int RunConvert(int argc, char** argv) {
  CLI::App app{"Read IN (any supported format) and write OUT (.obj .ply .off .glb) with\n"
               "positions and triangles only."};
  std::string in, out;
  bool json = false, ply_double = false;
  app.add_option("IN", in, "input mesh, or a .srm semi-regular file (its finest level)")->required();
  app.add_option("OUT", out, "output mesh: .obj .ply .off .glb")->required();
  app.add_flag("--ply-double", ply_double, "store PLY positions as double instead of float32");
  app.add_flag("--json", json, "print one JSON object describing what was written");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (IsSameFile(in, out)) return Fail("convert", out + ": is the input file; write the output elsewhere");
  ReadReport report;
  StatusOr<Mesh> mesh = EndsWith(in, ".srm") ? ReadFinestLevel(in) : ReadMeshDecodingGltf(in, &report);
  if (!mesh.ok()) return Fail("convert", mesh.status().message());
  WriteOptions options;
  options.ply_double_positions = ply_double;
  const Status written = WriteMesh(*mesh, out, options);
  if (!written.ok()) return Fail("convert", written.message());
  if (json) {
    nlohmann::json j;
    j["input"] = in;
    j["output"] = out;
    j["format"] = report.format;
    j["vertices"] = mesh->positions.size();
    j["faces"] = mesh->faces.size();
    j["dropped_unreferenced_vertices"] = report.dropped_unreferenced_vertices;
    j["polygons_triangulated"] = report.polygons_triangulated;
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%s -> %s: %zu vertices, %zu faces (%zu unreferenced vertices dropped)\n", in.c_str(),
                out.c_str(), mesh->positions.size(), mesh->faces.size(),
                report.dropped_unreferenced_vertices);
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("convert", "convert a mesh to OBJ / PLY / OFF / GLB (positions and triangles)",
                        RunConvert);

}  // namespace eqmesh::cli

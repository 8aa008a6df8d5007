// eqmesh perturb IN OUT --noise FRACTION: writes a deterministic noisy copy of
// IN (every vertex moved by exactly FRACTION x bbox diagonal, uniform random
// direction; see tools/perturb.h). The yardstick for `eqmesh compare`.
#include <cinttypes>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mesh_io/mesh_io.h"
#include "tools/perturb.h"
#include "tools/command.h"

namespace eqmesh::cli {
namespace {

std::string NameFile(const Status& status, const std::string& path) {
  return status.message().find(path) == std::string::npos ? path + ": " + status.message()
                                                           : status.message();
}

int RunPerturb(int argc, char** argv) {
  CLI::App app{
      "Move every vertex of IN by exactly FRACTION x (bbox diagonal) in a uniformly random\n"
      "direction (deterministic for a given --seed) and write OUT (format by extension)."};
  std::string in, out;
  double noise = 0.0;
  uint64_t seed = 0x5eed;
  bool json = false;
  app.add_option("in", in, "input mesh")->required();
  app.add_option("out", out, "output mesh: .obj .ply .off .glb")->required();
  app.add_option("--noise", noise, "displacement as a fraction of the bbox diagonal, e.g. 0.001")
      ->required()
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--seed", seed, "random seed")->check(CLI::NonNegativeNumber);
  app.add_flag("--json", json, "print one JSON object describing what was written");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (IsSameFile(in, out)) return Fail("perturb", out + ": is the input file; write the output elsewhere");
  StatusOr<Mesh> mesh = ReadMesh(in);
  if (!mesh.ok()) return Fail("perturb", NameFile(mesh.status(), in));
  const double diagonal = BoundingBoxDiagonal(*mesh);
  StatusOr<Mesh> noisy = PerturbVertices(*mesh, noise, seed);
  if (!noisy.ok()) return Fail("perturb", NameFile(noisy.status(), in));
  // Double-precision PLY so a .ply copy carries exactly the displaced positions.
  WriteOptions options;
  options.ply_double_positions = true;
  const Status written = WriteMesh(*noisy, out, options);
  if (!written.ok()) return Fail("perturb", NameFile(written, out));
  if (json) {
    nlohmann::json j;
    j["input"] = in;
    j["output"] = out;
    j["noise"] = noise;
    j["seed"] = seed;
    j["bbox_diagonal"] = diagonal;
    j["displacement"] = noise * diagonal;
    j["vertices"] = noisy->num_vertices();
    j["faces"] = noisy->num_faces();
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("wrote %s: %zu vertices moved by %.6g (%.6g x bbox diagonal %.6g), seed %" PRIu64 "\n",
                out.c_str(), noisy->num_vertices(), noise * diagonal, noise, diagonal, seed);
  }
  return 0;
}

}  // namespace

EQMESH_REGISTER_COMMAND("perturb", "write a deterministic noisy copy of a mesh (for compare demos)",
                        RunPerturb);

}  // namespace eqmesh::cli

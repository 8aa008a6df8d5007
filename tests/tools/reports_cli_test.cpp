// What the `eqmesh` commands tell a user about what they wrote: `info` on a
// compressed GLB, the per-primitive rate and PSNR of a .glb encode (the same
// stream a .eqm encode writes), quality targets that cannot be met (a clear
// error, no file), one message per broken GLB whichever command reads it, the
// colour error `compare` adds for textured glTF, and the folds it counts when
// asked.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "mesh_io/mesh_io.h"
#include "remesh/hard_shapes.h"
#include "test_support.h"
#include "tools/tool_runner.h"

namespace eqmesh::testing {
namespace {

// A bumpy 2562-vertex sphere: smooth enough to remesh at 70+ dB, detailed
// enough that a rate target chooses among several levels. The tests remesh it
// with 3 levels: the automatic count would refine to ~300k vertices.
std::string WriteBumpySphere(const ScratchDir& dir) {
  Mesh m = MakeIcosphere(4);
  for (Vec3& p : m.positions) p *= 1.0 + 0.05 * std::sin(5.0 * p.x()) * std::cos(4.0 * p.y());
  const std::string path = dir.Path("sphere.obj");
  EXPECT_TRUE(WriteMesh(m, path).ok());
  return path;
}

nlohmann::json Json(const ToolRun& r) {
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return nlohmann::json::parse(r.output, nullptr, false);
}

TEST(ReportsCli, InfoDescribesACompressedGlb) {
  const ScratchDir dir("reports_info");
  const std::string glb = dir.Path("sphere.glb");
  const nlohmann::json encoded = Json(RunTool("encode " + WriteBumpySphere(dir) + " " + glb + " --levels 3 --bpv 4 --json"));
  ASSERT_FALSE(encoded.is_discarded());
  const nlohmann::json info = Json(RunTool("info " + glb + " --json"));
  ASSERT_FALSE(info.is_discarded());
  ASSERT_EQ(info["primitives"].size(), 1u);
  const nlohmann::json& p = info["primitives"][0];
  EXPECT_TRUE(p["compressed"].get<bool>());
  EXPECT_EQ(p["levels"], encoded["primitives"][0]["levels"]);
  EXPECT_EQ(p["stream_bytes"], encoded["primitives"][0]["stream_bytes"]);
  const std::vector<uint64_t> prefixes = p["prefix_bytes"].get<std::vector<uint64_t>>();
  ASSERT_EQ(prefixes.size(), p["levels"].get<size_t>() + 1);
  for (size_t k = 1; k < prefixes.size(); ++k) EXPECT_LT(prefixes[k - 1], prefixes[k]);
  EXPECT_EQ(prefixes.back(), p["stream_bytes"].get<uint64_t>());
  // The decoded geometry is what `decode` writes.
  EXPECT_EQ(p["vertices"], encoded["primitives"][0]["output_vertices"]);
  EXPECT_EQ(info["referenced_vertices"], p["vertices"]);
  EXPECT_TRUE(info["manifold"].get<bool>());
  const ToolRun table = RunTool("info " + glb);
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("EXT_normal_mesh_compression"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("bytes to level 0.."), std::string::npos) << table.output;
}

TEST(ReportsCli, GlbEncodeReportsEachPrimitivesRateAndWritesTheEqmStream) {
  const ScratchDir dir("reports_glb");
  const std::string in = WriteBumpySphere(dir);
  const ToolRun glb = RunTool("encode " + in + " " + dir.Path("sphere.glb") + " --levels 3 --bpv 3");
  ASSERT_EQ(glb.exit_code, 0) << glb.output;
  EXPECT_NE(glb.output.find("in streams"), std::string::npos) << glb.output;
  EXPECT_NE(glb.output.find("bits per input vertex"), std::string::npos) << glb.output;
  EXPECT_NE(glb.output.find("PSNR"), std::string::npos) << glb.output;
  // One rate target, one stream: the GLB carries what `encode IN x.eqm` writes.
  const nlohmann::json e = Json(RunTool("encode " + in + " " + dir.Path("sphere.eqm") + " --levels 3 --bpv 3 --json"));
  ASSERT_FALSE(e.is_discarded());
  const std::string stream = " -> " + std::to_string(e["bytes"].get<size_t>()) + "-byte stream";
  EXPECT_NE(glb.output.find(stream), std::string::npos) << stream << " in " << glb.output;
  const std::string levels = ", " + std::to_string(e["levels"].get<int>()) + " levels";
  EXPECT_NE(glb.output.find(levels), std::string::npos) << levels << " in " << glb.output;
}

TEST(ReportsCli, UnreachablePsnrTargetFailsNamingTheBestAndWritesNothing) {
  const ScratchDir dir("reports_psnr");
  const std::string in = WriteBumpySphere(dir);
  const std::string out = dir.Path("sphere.eqm");
  const ToolRun r = RunTool("encode " + in + " " + out + " --levels 3 --psnr 150");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("PSNR target 150.00 dB is out of reach"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" measures "), std::string::npos) << r.output;
  EXPECT_FALSE(FileExists(out));
  // A floor no primitive of the GLB meets leaves it unchanged; with nothing
  // compressed the run fails and writes nothing.
  const std::string glb = dir.Path("sphere.glb");
  const ToolRun g = RunTool("encode " + in + " " + glb + " --levels 3 --base-vertices 200 --lambda 0.02 --min-psnr 200");
  EXPECT_NE(g.exit_code, 0) << g.output;
  EXPECT_NE(g.output.find("below the 200.00 dB floor"), std::string::npos) << g.output;
  EXPECT_FALSE(FileExists(glb));
}

// Base vertex count from `eqmesh remesh`'s one-line report ("... -> base N, ..."),
// 0 when absent. (Without --json: that report measures with 1M+ samples.)
size_t ReportedBaseVertices(const ToolRun& r) {
  const size_t at = r.output.find("-> base ");
  return at == std::string::npos ? 0 : std::stoul(r.output.substr(at + 8));
}

// `eqmesh remesh` holds its output to 80 dB by default: a spiky star whose
// 2 % base loses the spike tips (76.6 dB at 4 levels) is remeshed again on a
// finer base. A floor out of any base's reach still writes the best remesh,
// with a warning naming it. (The floor's mechanism itself: stage_test.cpp.)
TEST(ReportsCli, RemeshHoldsItsDefaultFloorAndWarnsWhereItCannot) {
  const ScratchDir dir("reports_remesh_floor");
  const std::string in = dir.Path("star.obj");
  ASSERT_TRUE(WriteMesh(MakeSpikyStar(), in).ok());
  const std::string out = dir.Path("star.ply");
  const ToolRun plain = RunTool("remesh " + in + " " + out + " --levels 4 --min-psnr 0");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const ToolRun held = RunTool("remesh " + in + " " + out + " --levels 4");
  ASSERT_EQ(held.exit_code, 0) << held.output;
  EXPECT_EQ(held.output.find("warning"), std::string::npos) << held.output;
  ASSERT_GT(ReportedBaseVertices(plain), 0u) << plain.output;
  EXPECT_GT(ReportedBaseVertices(held), ReportedBaseVertices(plain)) << plain.output << held.output;
  const std::string unreachable = dir.Path("unreachable.ply");
  const ToolRun r = RunTool("remesh " + in + " " + unreachable + " --levels 2 --min-psnr 200");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the remesh measures"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("below the 200 dB floor"), std::string::npos) << r.output;
  EXPECT_TRUE(FileExists(unreachable));
}

// With --repair the remesher works on the repaired input, and its fold count
// is taken against that: a sphere turned inside out is remeshed facing out,
// which is no fold (against the file as read every face would count).
TEST(ReportsCli, RemeshCountsFoldsAgainstTheRepairedInput) {
  const ScratchDir dir("reports_remesh_repaired");
  Mesh m = MakeIcosphere(3);
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  const std::string in = dir.Path("inside_out.obj");
  ASSERT_TRUE(WriteMesh(m, in).ok());
  const nlohmann::json j = Json(RunTool("remesh " + in + " " + dir.Path("out.ply") + " --levels 2 --repair --json"));
  ASSERT_FALSE(j.is_discarded());
  EXPECT_NE(j["notes"].dump().find("turned outward"), std::string::npos) << j.dump();
  EXPECT_GT(j["output_faces"].get<size_t>(), 0u);
  EXPECT_EQ(j["flipped_faces"].get<size_t>(), 0u) << j.dump();
}

TEST(ReportsCli, BrokenGlbGetsOneMessageFromEveryCommand) {
  const ScratchDir dir("reports_broken");
  const std::string empty = dir.Path("empty.glb");
  WriteText(empty, "");
  for (const std::string& command : {"info " + empty, "decode " + empty + " " + dir.Path("x.ply"),
                                     "encode " + empty + " " + dir.Path("x.glb"), "compare " + empty + " " + empty}) {
    const ToolRun r = RunTool(command);
    EXPECT_NE(r.exit_code, 0) << command;
    EXPECT_NE(r.output.find("empty.glb: empty file"), std::string::npos) << command << ": " << r.output;
  }
  // A GLB cut short: the same chunk offset whichever reader meets it first.
  const std::string glb = dir.Path("sphere.glb");
  ASSERT_EQ(RunTool("encode " + WriteBumpySphere(dir) + " " + glb + " --levels 3 --bpv 3").exit_code, 0);
  const std::vector<uint8_t> bytes = ReadFileOrEmpty(glb);
  ASSERT_GT(bytes.size(), 1200u);
  const std::string cut = dir.Path("cut.glb");
  WriteText(cut, std::string(bytes.begin(), bytes.begin() + 1200));
  std::string first;
  for (const std::string& command : {"info " + cut, "decode " + cut + " " + dir.Path("y.ply"),
                                     "encode " + cut + " " + dir.Path("y.glb"), "compare " + cut + " " + cut}) {
    const ToolRun r = RunTool(command);
    EXPECT_NE(r.exit_code, 0) << command;
    const size_t at = r.output.find("GLB chunk at byte ");
    ASSERT_NE(at, std::string::npos) << command << ": " << r.output;
    const std::string message = r.output.substr(at, r.output.find('\n', at) - at);
    if (first.empty()) first = message;
    EXPECT_EQ(message, first) << command;
  }
}

// The appearance meter: two glTF scenes of which one is textured get
// color_psnr_db on the geometry's samples; meshes without colour get none.
TEST(ReportsCli, CompareMeasuresColourOfTexturedGltfOnly) {
  if (!HaveSharedMeshes()) GTEST_SKIP() << "no ../shared/meshes";
  const std::string duck = SharedPath("meshes/textured/duck.glb");
  const nlohmann::json same = Json(RunTool("compare " + duck + " " + duck + " --samples 20000 --json"));
  ASSERT_TRUE(same.contains("color_psnr_db")) << same.dump();
  // null: an exact match (JSON has no infinity), as psnr_db.
  EXPECT_TRUE(same["color_psnr_db"].is_null() || same["color_psnr_db"].get<double>() > 100.0) << same.dump();
  EXPECT_LT(same["color_rms"].get<double>(), 0.01);
  const ScratchDir dir("reports_colour");
  const std::string sphere = WriteBumpySphere(dir);
  const nlohmann::json plain = Json(RunTool("compare " + sphere + " " + sphere + " --samples 20000 --json"));
  EXPECT_FALSE(plain.contains("color_psnr_db")) << plain.dump();
}

// `compare --folds`: faces of OTHER turned against IN are counted, and only
// when asked.
TEST(ReportsCli, CompareCountsFlippedFacesWhenAsked) {
  const ScratchDir dir("reports_folds");
  const std::string sphere = WriteBumpySphere(dir);
  StatusOr<Mesh> turned = ReadMesh(sphere);
  ASSERT_TRUE(turned.ok());
  for (const size_t f : {size_t{0}, size_t{100}, size_t{2000}}) std::swap(turned->faces[f][1], turned->faces[f][2]);
  const std::string other = dir.Path("turned.obj");
  ASSERT_TRUE(WriteMesh(*turned, other).ok());
  const std::string samples = " --samples 20000 --json";
  const nlohmann::json folded = Json(RunTool("compare " + sphere + " " + other + " --folds" + samples));
  EXPECT_EQ(folded["flipped_faces"], 3) << folded.dump();
  EXPECT_EQ(folded["degenerate_faces"], 0) << folded.dump();
  const nlohmann::json same = Json(RunTool("compare " + sphere + " " + sphere + " --folds" + samples));
  EXPECT_EQ(same["flipped_faces"], 0) << same.dump();
  const nlohmann::json unasked = Json(RunTool("compare " + sphere + " " + other + samples));
  EXPECT_FALSE(unasked.contains("flipped_faces")) << unasked.dump();
  const ToolRun table = RunTool("compare " + sphere + " " + other + " --folds --samples 20000");
  EXPECT_NE(table.output.find("3 flipped"), std::string::npos) << table.output;
}

}  // namespace
}  // namespace eqmesh::testing

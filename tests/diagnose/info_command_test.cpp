// `eqmesh info` end to end: JSON shape and values, table output, clear errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "mesh_io/mesh_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

struct RunResult {
  int exit_code = -1;
  std::string out;
};

// Runs the tool with stderr folded into the output when `with_stderr`.
RunResult RunTool(const std::string& args, bool with_stderr = false) {
  const std::string cmd = std::string(EQMESH_TOOL) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "eqmesh_info_" + std::to_string(getpid()) + "_" + name;
}

TEST(InfoCommand, JsonForATorus) {
  const std::string path = TempPath("torus.obj");
  ASSERT_TRUE(WriteMesh(testing::MakeTorus(12, 6), path).ok());
  const RunResult r = RunTool("info " + path + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // exactly one object
  ASSERT_TRUE(j.is_object());
  for (const char* key : {"file", "format", "vertices", "referenced_vertices", "dropped_unreferenced_vertices",
                          "faces", "boundary_edges", "boundary_loops", "non_manifold_edges",
                          "non_manifold_vertices", "inconsistent_edges", "components", "closed_components",
                          "genus", "degenerate_faces", "duplicate_positions", "bbox_diagonal", "manifold",
                          "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["file"], path);
  EXPECT_EQ(j["format"], "obj");
  EXPECT_EQ(j["vertices"], 72);
  EXPECT_EQ(j["faces"], 144);
  EXPECT_EQ(j["boundary_edges"], 0);
  EXPECT_EQ(j["genus"], nlohmann::json::array({1}));
  EXPECT_EQ(j["manifold"], true);
  std::remove(path.c_str());
}

TEST(InfoCommand, TableNamesTheFile) {
  const std::string path = TempPath("disc.off");
  ASSERT_TRUE(WriteMesh(testing::MakeDisc(3), path).ok());
  const RunResult r = RunTool("info " + path);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find(path), std::string::npos);
  EXPECT_NE(r.out.find("18 edges in 1 loops"), std::string::npos) << r.out;
  std::remove(path.c_str());
}

TEST(InfoCommand, CowJsonReportsThePinchedVertex) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  const RunResult r = RunTool("info " + testing::SharedPath("meshes/small/cow.ply") + " --json");
  ASSERT_EQ(r.exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["non_manifold_vertices"], 1);
  EXPECT_EQ(j["manifold"], false);
  EXPECT_EQ(j["format"], "ply");
}

TEST(InfoCommand, MissingFileIsAOneLineErrorNamingIt) {
  const std::string path = TempPath("does_not_exist.obj");
  const RunResult r = RunTool("info " + path + " --json", /*with_stderr=*/true);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find(path), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;
}

TEST(InfoCommand, HelpAndMissingArgument) {
  EXPECT_EQ(RunTool("info --help").exit_code, 0);
  EXPECT_NE(RunTool("info").exit_code, 0);
}

}  // namespace
}  // namespace eqmesh

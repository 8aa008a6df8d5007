// Every input a fuzz target (fuzz/) once failed on, minimized, replayed through the
// very check the target runs (fuzz/fuzz_checks.h): each must now give a clean error
// or a result within the entry point's promises. data/<target>/ holds the files;
// the README there says which bug each one found.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/fuzz_checks.h"
#include "gltf/gltf_loader.h"

namespace eqmesh {
namespace {

namespace fs = std::filesystem;

std::string Check(const std::string& target, const std::vector<uint8_t>& bytes) {
  const uint8_t* data = bytes.data();
  if (target == "eqm_decode") return fuzz::CheckStreamDecoder(data, bytes.size());
  if (target == "gltf_load") return fuzz::CheckGltfLoader(data, bytes.size());
  if (target == "read_obj") return fuzz::CheckMeshReader("obj", data, bytes.size());
  if (target == "read_ply") return fuzz::CheckMeshReader("ply", data, bytes.size());
  if (target == "read_off") return fuzz::CheckMeshReader("off", data, bytes.size());
  return "no such fuzz target: " + target;
}

const fs::path kDataDir = fs::path(EQMESH_SOURCE_DIR) / "tests/fuzz_regressions/data";

// The targets with a data/<target>/ folder: one test each, so a target without
// reproducers yet is no test at all rather than a skipped one.
std::vector<std::string> TargetsWithReproducers() {
  std::vector<std::string> targets;
  for (const char* target : {"eqm_decode", "gltf_load", "read_obj", "read_ply", "read_off"}) {
    if (fs::is_directory(kDataDir / target)) targets.push_back(target);
  }
  return targets;
}

class FuzzRegressions : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzRegressions, EveryReproducerIsHandled) {
  const fs::path dir = kDataDir / GetParam();
  size_t files = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(Check(GetParam(), bytes), "") << entry.path();
    ++files;
  }
  EXPECT_GT(files, 0u) << dir << " holds no reproducer";
  RecordProperty("files", static_cast<int>(files));
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegressions, ::testing::ValuesIn(TargetsWithReproducers()));

// Found by review of what the gltf_load target could reach: bytes loaded from
// memory have no directory, so their external URIs must not resolve at all (an
// absolute one used to be read as is, a relative one against the working directory).
TEST(FuzzRegressions, GltfFromMemoryReadsNoLocalFile) {
  const std::string local = std::string(EQMESH_SOURCE_DIR) + "/README.md";
  ASSERT_TRUE(fs::exists(local));
  for (const std::string& uri : {local, std::string("README.md"), "file://" + local}) {
    const std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"uri":")" + uri +
                             R"(","byteLength":4}],"bufferViews":[{"buffer":0,"byteLength":4}],)"
                             R"("accessors":[{"bufferView":0,"componentType":5121,"count":4,"type":"SCALAR"}]})";
    const std::vector<uint8_t> file(json.begin(), json.end());
    auto model = gltf::LoadGltfFromBytes(file, "memory.gltf");
    ASSERT_FALSE(model.ok()) << uri << " was read";
    EXPECT_EQ(model.status().code(), StatusCode::kParseError) << model.status().ToString();
  }
}

}  // namespace
}  // namespace eqmesh

// The shared test meshes load with the counts in meshes/MANIFEST.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "mesh_io/mesh_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

struct Expected {
  const char* path;
  size_t vertices;  // after dropping unreferenced ones
  size_t faces;
  size_t dropped;
  const char* format;
};

// Computed here rather than with CountReferencedVertices so that this test checks
// the reader against an independent count.
size_t ReferencedVertices(const Mesh& m) {
  std::vector<bool> used(m.num_vertices(), false);
  size_t n = 0;
  for (const Face& f : m.faces) {
    for (uint32_t i : f) {
      if (used[i]) continue;
      used[i] = true;
      ++n;
    }
  }
  return n;
}

class SharedMesh : public ::testing::TestWithParam<Expected> {};

TEST_P(SharedMesh, LoadsWithManifestCounts) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  const Expected e = GetParam();
  ReadReport report;
  auto m = ReadMesh(testing::SharedPath(e.path), &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, e.format);
  EXPECT_EQ(m->num_vertices(), e.vertices);
  EXPECT_EQ(m->num_faces(), e.faces);
  EXPECT_EQ(report.dropped_unreferenced_vertices, e.dropped);
  EXPECT_EQ(m->num_vertices() + report.dropped_unreferenced_vertices, e.vertices + e.dropped);
  EXPECT_EQ(ReferencedVertices(*m), m->num_vertices());
}

// cow.ply is listed as ascii in the manifest but is stored as binary tristrips.
INSTANTIATE_TEST_SUITE_P(
    Manifest, SharedMesh,
    ::testing::Values(Expected{"meshes/small/bunny_npm.obj", 1839, 3674, 0, "obj"},
                      Expected{"meshes/small/fandisk.obj", 6475, 12946, 0, "obj"},
                      Expected{"meshes/small/skull_low_resolution.obj", 5154, 10312, 0, "obj"},
                      Expected{"meshes/small/rocker-arm.off", 10044, 20088, 0, "off"},
                      Expected{"meshes/small/max-planck_10k.obj", 10000, 19996, 0, "obj"},
                      Expected{"meshes/small/cow.ply", 2903, 5804, 0, "ply"},
                      Expected{"meshes/bench/stanford-bunny.obj", 34834, 69451, 1113, "obj"},
                      Expected{"meshes/bench/igea.ply", 134345, 268686, 0, "ply"},
                      Expected{"meshes/bench/horse.ply", 48485, 96966, 0, "ply"}),
    [](const ::testing::TestParamInfo<Expected>& param_info) {
      std::string name = param_info.param.path;
      name = name.substr(name.find_last_of('/') + 1);
      std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
      return name;
    });

// The two gzip dragons in one test (the slow one the suite allows).
TEST(SharedMeshGzip, DragonsLoad) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  ReadReport report;
  auto dragon = ReadMesh(testing::SharedPath("meshes/bench/dragon_vrip.ply.gz"), &report);
  ASSERT_TRUE(dragon.ok()) << dragon.status().ToString();
  EXPECT_EQ(dragon->num_faces(), 871414u);
  EXPECT_EQ(dragon->num_vertices(), 437645u);  // every stored vertex is used
  EXPECT_EQ(report.dropped_unreferenced_vertices, 0u);
  EXPECT_EQ(ReferencedVertices(*dragon), dragon->num_vertices());
  auto res2 = ReadMesh(testing::SharedPath("meshes/bench/dragon_vrip_res2.ply.gz"), &report);
  ASSERT_TRUE(res2.ok()) << res2.status().ToString();
  EXPECT_EQ(res2->num_faces(), 202520u);
  EXPECT_EQ(res2->num_vertices(), 100207u);  // the crude decimation left 43 orphans
  EXPECT_EQ(report.dropped_unreferenced_vertices, 43u);
}

}  // namespace
}  // namespace eqmesh

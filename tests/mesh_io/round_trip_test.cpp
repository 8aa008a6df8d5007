// write -> read preserves the mesh: exactly for OBJ, OFF and double PLY, to float
// precision for float PLY and GLB.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io_test_util.h"
#include "mesh_io/mesh_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// An icosphere with awkward coordinates (not representable in float, tiny and large
// magnitudes) so that precision loss would show.
Mesh AwkwardSphere() {
  Mesh m = testing::MakeIcosphere(2, 1.0 / 3.0);
  for (size_t i = 0; i < m.positions.size(); ++i) m.positions[i] += Vec3(1e-7 * static_cast<double>(i), 12345.678, -0.1);
  return m;
}

void ExpectSameMesh(const Mesh& a, const Mesh& b, double tolerance) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  for (size_t f = 0; f < a.num_faces(); ++f) ASSERT_EQ(a.faces[f], b.faces[f]) << "face " << f;
  for (size_t v = 0; v < a.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      if (tolerance == 0.0) ASSERT_EQ(a.positions[v][k], b.positions[v][k]) << "vertex " << v;
      else ASSERT_NEAR(a.positions[v][k], b.positions[v][k], tolerance * std::abs(a.positions[v][k]) + 1e-30) << v;
    }
  }
}

struct Case {
  const char* extension;
  bool ply_double;
  double tolerance;  // relative
};

class RoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(RoundTrip, PreservesTheMesh) {
  const Case c = GetParam();
  const Mesh original = AwkwardSphere();
  const std::string path = testing::TempPath(std::string("sphere.") + c.extension);
  WriteOptions options;
  options.ply_double_positions = c.ply_double;
  ASSERT_TRUE(WriteMesh(original, path, options).ok());
  ReadReport report;
  auto back = ReadMesh(path, &report);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(report.format, c.extension);
  EXPECT_EQ(report.dropped_unreferenced_vertices, 0u);
  ExpectSameMesh(original, *back, c.tolerance);
  std::remove(path.c_str());
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip,
                         ::testing::Values(Case{"obj", false, 0.0}, Case{"off", false, 0.0},
                                           Case{"ply", true, 0.0}, Case{"ply", false, 6e-8},
                                           Case{"glb", false, 6e-8}),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           return std::string(param_info.param.extension) + (param_info.param.ply_double ? "_double" : "");
                         });

TEST(WriteGlb, LayoutFollowsTheGlbContainerRules) {
  const Mesh square = testing::MakeSquare();  // 2 faces: 6 uint16 indices = 12 bytes
  auto bytes = WriteMeshToBytes(square, "glb");
  ASSERT_TRUE(bytes.ok());
  const std::vector<uint8_t>& b = *bytes;
  ASSERT_GE(b.size(), 28u);
  auto u32 = [&b](size_t at) { return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 | uint32_t{b[at + 3]} << 24; };
  EXPECT_EQ(u32(0), 0x46546C67u);
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), b.size());
  const uint32_t json_len = u32(12);
  EXPECT_EQ(json_len % 4, 0u);
  EXPECT_EQ(u32(16), 0x4E4F534Au);
  const size_t bin_at = 20 + json_len;
  EXPECT_EQ(u32(bin_at + 4), 0x004E4942u);
  EXPECT_EQ(bin_at + 8 + u32(bin_at), b.size());
  const std::string json(b.begin() + 20, b.begin() + 20 + json_len);
  EXPECT_NE(json.find("\"componentType\":5123"), std::string::npos);
  EXPECT_NE(json.find("\"min\":[0,0,0],\"max\":[1,1,0]"), std::string::npos) << json;
}

TEST(WriteMesh, UsesUint32IndicesBeyond65535Vertices) {
  Mesh m = testing::MakeSquare();
  m.positions.resize(70000, Vec3(0.5, 0.5, 1));
  m.faces.push_back({3, 2, 69999});
  auto bytes = WriteMeshToBytes(m, "glb");
  ASSERT_TRUE(bytes.ok());
  const std::string all(bytes->begin(), bytes->end());
  EXPECT_NE(all.find("\"componentType\":5125"), std::string::npos);
  auto back = ReadMeshFromBytes(*bytes, "glb", "wide.glb");
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->num_faces(), 3u);
}

TEST(WriteMesh, RefusesInvalidMeshes) {
  Mesh bad_index = testing::MakeSquare();
  bad_index.faces[1][2] = 4;
  const Status s = WriteMesh(bad_index, testing::TempPath("bad.obj"));
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("bad.obj"), std::string::npos);
  Mesh nan = testing::MakeSquare();
  nan.positions[2].y() = std::nan("");
  EXPECT_FALSE(WriteMeshToBytes(nan, "ply").ok());
  Mesh huge = testing::MakeSquare();
  huge.positions[0].x() = 1e300;
  EXPECT_FALSE(WriteMeshToBytes(huge, "glb").ok());
  EXPECT_TRUE(WriteMeshToBytes(huge, "obj").ok());
  EXPECT_FALSE(WriteMeshToBytes(Mesh(), "glb").ok());
  EXPECT_FALSE(WriteMeshToBytes(bad_index, "stl").ok());
  EXPECT_FALSE(WriteMesh(testing::MakeSquare(), "/nonexistent-dir/x.obj").ok());
}

}  // namespace
}  // namespace eqmesh

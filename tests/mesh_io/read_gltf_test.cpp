// glTF scene flattening: node transforms, mirroring, skipped primitive modes,
// non-indexed primitives, scene selection and accessor bounds.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "io_test_util.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh {
namespace {

std::string Base64(const std::vector<uint8_t>& in) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t v = uint32_t{in[i]} << 16;
    if (i + 1 < in.size()) v |= uint32_t{in[i + 1]} << 8;
    if (i + 2 < in.size()) v |= in[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < in.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

// One triangle: 36 bytes of float positions then 3 uint16 indices (+2 padding).
std::vector<uint8_t> TriangleBuffer() {
  std::vector<uint8_t> b;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) testing::AppendScalar(&b, f, false);
  for (int i : {0, 1, 2, 0}) testing::AppendScalar(&b, static_cast<uint16_t>(i), false);
  return b;
}

std::string Gltf(const std::string& scenes_and_nodes, const std::string& accessors,
                 const std::string& buffer_uri = "") {
  const std::vector<uint8_t> buf = TriangleBuffer();
  const std::string uri = buffer_uri.empty() ? "data:application/octet-stream;base64," + Base64(buf) : buffer_uri;
  return "{\"asset\":{\"version\":\"2.0\"}," + scenes_and_nodes +
         "\"meshes\":[{\"primitives\":["
         "{\"attributes\":{\"POSITION\":0},\"indices\":1},"
         "{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":1},"
         "{\"attributes\":{\"POSITION\":0},\"mode\":4}]}],"
         "\"accessors\":[" + accessors + "],"
         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
         "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
         "\"buffers\":[{\"byteLength\":" + std::to_string(buf.size()) +
         ",\"uri\":\"" + uri + "\"}]}";
}

const char* kGoodAccessors =
    "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}";

const char* kScene =
    "\"scene\":1,\"scenes\":[{\"nodes\":[3]},{\"nodes\":[0,2]}],"
    "\"nodes\":[{\"translation\":[10,0,0],\"children\":[1]},{\"mesh\":0,\"scale\":[2,2,2]},"
    "{\"mesh\":0,\"matrix\":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]},{\"mesh\":0}],";

TEST(ReadGltf, FlattensTheDefaultSceneWithTransforms) {
  ReadReport report;
  auto m = ReadMeshFromBytes(testing::ToBytes(Gltf(kScene, kGoodAccessors)), "gltf", "scene.gltf", &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.format, "gltf");
  EXPECT_EQ(report.primitives_skipped, 2u);  // the LINES primitive, once per instance
  ASSERT_EQ(m->num_vertices(), 12u);
  ASSERT_EQ(m->num_faces(), 4u);
  // Node 1: translate(10) * scale(2).
  EXPECT_EQ(m->positions[1], Vec3(12, 0, 0));
  EXPECT_EQ(m->positions[5], Vec3(10, 2, 0));
  EXPECT_EQ(m->faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(m->faces[1], (Face{3, 4, 5}));  // non-indexed
  // Node 2 mirrors x, so the winding is flipped back to counter-clockwise.
  EXPECT_EQ(m->positions[7], Vec3(-1, 0, 0));
  EXPECT_EQ(m->faces[2], (Face{6, 8, 7}));
  EXPECT_EQ(m->faces[3], (Face{9, 11, 10}));
}

TEST(ReadGltf, WithoutScenesEveryRootNodeCounts) {
  const char* nodes = "\"nodes\":[{\"children\":[1]},{\"mesh\":0,\"translation\":[0,0,5]},{\"mesh\":0}],";
  auto m = ReadMeshFromBytes(testing::ToBytes(Gltf(nodes, kGoodAccessors)), "gltf", "noscene.gltf");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->num_faces(), 4u);
  EXPECT_EQ(m->positions[0], Vec3(0, 0, 5));
  EXPECT_EQ(m->positions[6], Vec3(0, 0, 0));
}

TEST(ReadGltf, AccessorOutsideItsBufferViewIsAnError) {
  const char* bad =
      "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
      "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}";
  auto m = ReadMeshFromBytes(testing::ToBytes(Gltf(kScene, bad)), "gltf", "bounds.gltf");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("bounds.gltf"), std::string::npos);
  EXPECT_NE(m.status().message().find("exceed"), std::string::npos) << m.status().message();
}

TEST(ReadGltf, HugeAccessorOffsetIsAnError) {
  const char* bad =
      "{\"bufferView\":0,\"byteOffset\":18446744073709551600,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
      "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}";
  auto m = ReadMeshFromBytes(testing::ToBytes(Gltf(kScene, bad)), "gltf", "offset.gltf");
  EXPECT_FALSE(m.ok());
}

TEST(ReadGltf, IndexOutOfRangeIsAnError) {
  std::string json = Gltf(kScene, kGoodAccessors);
  // Same file, but the index accessor reads the float 1.0 of vertex 1 as uint16
  // indices 0, 16256, 0.
  const std::string from = "{\"bufferView\":1,\"componentType\":5123";
  json.replace(json.find(from), from.size(), "{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5123");
  auto m = ReadMeshFromBytes(testing::ToBytes(json), "gltf", "index.gltf");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("out of range"), std::string::npos) << m.status().message();
}

TEST(ReadGltf, NodeCycleIsAnError) {
  const char* nodes = "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"children\":[1]},{\"mesh\":0,\"children\":[0]}],";
  auto m = ReadMeshFromBytes(testing::ToBytes(Gltf(nodes, kGoodAccessors)), "gltf", "cycle.gltf");
  EXPECT_FALSE(m.ok());
}

TEST(ReadGltf, ExternalBufferIsFoundBesideTheFile) {
  const std::string bin_path = testing::TempPath("tri.bin");
  testing::WriteFile(bin_path, TriangleBuffer());
  const std::string bin_name = bin_path.substr(bin_path.find_last_of('/') + 1);
  const std::string gltf_path = testing::TempPath("external.gltf");
  testing::WriteFile(gltf_path, Gltf(kScene, kGoodAccessors, bin_name));
  auto m = ReadMesh(gltf_path);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->num_faces(), 4u);
  std::remove(bin_path.c_str());
  auto missing = ReadMesh(gltf_path);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("external.gltf"), std::string::npos);
  std::remove(gltf_path.c_str());
}

TEST(ReadGltf, MutatedGlbNeverCrashes) {
  const auto glb = WriteMeshToBytes(testing::MakeSquare(), "glb");
  ASSERT_TRUE(glb.ok());
  std::mt19937 rng(5);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<uint8_t> b = *glb;
    for (int k = 0; k < 3; ++k) b[rng() % b.size()] = static_cast<uint8_t>(rng());
    if (trial % 7 == 0) b.resize(rng() % b.size());
    auto m = ReadMeshFromBytes(b, "glb", "mutant.glb");
    if (!m.ok()) {
      EXPECT_NE(m.status().message().find("mutant.glb"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace eqmesh

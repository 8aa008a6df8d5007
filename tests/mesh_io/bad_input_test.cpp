// Hostile and broken inputs: each must give a non-OK Status whose message names the
// file, never a crash, hang or huge allocation (the ASan build runs these too).
#include <gtest/gtest.h>

#include <random>

#include "io_test_util.h"
#include "mesh_io/file_bytes.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh {
namespace {

using testing::ToBytes;

// Writes `bytes` to a file called `file_name`, reads it back and expects an error
// naming the file and containing `expect` (if not empty).
void ExpectReadError(const std::string& file_name, const std::vector<uint8_t>& bytes, const std::string& expect) {
  const std::string path = testing::TempPath(file_name);
  testing::WriteFile(path, bytes);
  auto m = ReadMesh(path);
  ASSERT_FALSE(m.ok()) << file_name << " was accepted";
  EXPECT_NE(m.status().message().find(path), std::string::npos) << m.status().message();
  if (!expect.empty()) {
    EXPECT_NE(m.status().message().find(expect), std::string::npos) << m.status().message();
  }
  EXPECT_EQ(m.status().message().find('\n'), std::string::npos) << "multi-line: " << m.status().message();
  std::remove(path.c_str());
}

void ExpectReadError(const std::string& file_name, const std::string& text, const std::string& expect) {
  ExpectReadError(file_name, ToBytes(text), expect);
}

const char* kPlyHeader3 =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(BadInput, MissingFile) {
  auto m = ReadMesh("/nonexistent/dir/nothing.obj");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kIoError);
  EXPECT_NE(m.status().message().find("nothing.obj"), std::string::npos);
}

TEST(BadInput, EmptyFileInEveryFormat) {
  for (const char* name : {"e.obj", "e.ply", "e.off", "e.gltf", "e.glb", "e.obj.gz", "e.stl"}) {
    ExpectReadError(name, std::string(), "");
  }
}

TEST(BadInput, BinaryFileNamedObj) {
  std::vector<uint8_t> noise(4096);
  std::mt19937 rng(7);
  for (uint8_t& b : noise) b = static_cast<uint8_t>(rng());
  noise[100] = 0;
  ExpectReadError("noise.obj", noise, "binary");
  // Text without a single OBJ statement.
  ExpectReadError("prose.obj", "This is not a mesh.\nNot at all.\n", "not an OBJ file");
}

TEST(BadInput, FaceIndexOutOfRange) {
  ExpectReadError("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 40000\n",
                  "line 5: face index 40000 out of range (3 vertices)");
  ExpectReadError("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n", "line 3");
  ExpectReadError("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4");
  ExpectReadError("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 6: face index 3 out of range");
  ExpectReadError("range.ply", std::string(kPlyHeader3) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "face index 7 out of range");
  ExpectReadError("negative.ply", std::string(kPlyHeader3) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "face index -1");
}

TEST(BadInput, NonFiniteCoordinates) {
  ExpectReadError("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "vertex 1");
  ExpectReadError("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", "vertex 2");
  ExpectReadError("nan.ply", std::string(kPlyHeader3) + "0 0 0\n1 0 0\n0 1 -nan\n3 0 1 2\n", "non-finite");
  // 1e999 overflows double: rejected as a bad number rather than silently inf.
  ExpectReadError("big.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n", "line 2");
}

TEST(BadInput, LyingElementCountsFailBeforeAllocating) {
  ExpectReadError("lie.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
                  "property float y\nproperty float z\nend_header\n\x01\x02",
                  "1000000000000 'vertex' elements");
  ExpectReadError("lie_ascii.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
                  "'face' elements");
  ExpectReadError("lie.off", "OFF\n1000000000000 1 0\n0 0 0\n", "header declares");
  // Counts that overflow 64-bit arithmetic.
  ExpectReadError("overflow.ply",
                  "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nend_header\n", "");
  // A list declaring more items than the file has.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  std::vector<uint8_t> bytes = ToBytes(ply);
  bytes.resize(bytes.size() + 36, 0);
  testing::AppendScalar<uint32_t>(&bytes, 0x7fffffffu, false);
  ExpectReadError("list.ply", bytes, "truncated");
}

TEST(BadInput, TruncatedBinaryPly) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<uint8_t> bytes = ToBytes(ply);
  bytes.resize(bytes.size() + 36, 0);
  bytes.push_back(3);
  for (int i = 0; i < 2; ++i) testing::AppendScalar<int32_t>(&bytes, i, false);  // one index short
  ExpectReadError("trunc.ply", bytes, "truncated");
}

TEST(BadInput, MalformedPlyHeaders) {
  ExpectReadError("nomagic.ply", "plx\nformat ascii 1.0\nend_header\n", "");
  ExpectReadError("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "end_header");
  ExpectReadError("badtype.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n0\n", "line 4");
  ExpectReadError("badformat.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", "format");
  ExpectReadError("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", "'y'");
  ExpectReadError("noface.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "end_header\n0 0 0\n1 0 0\n0 1 0\n",
                  "no faces");
}

TEST(BadInput, GarbageGlbAndGltf) {
  std::vector<uint8_t> glb = ToBytes("glTF");
  for (uint32_t v : {2u, 1000u, 500u, 0x4E4F534Au}) testing::AppendScalar(&glb, v, false);
  glb.resize(64, 'x');
  ExpectReadError("garbage.glb", glb, "");
  std::vector<uint8_t> noise(300);
  std::mt19937 rng(11);
  for (uint8_t& b : noise) b = static_cast<uint8_t>(rng());
  ExpectReadError("noise.glb", noise, "");
  ExpectReadError("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [", "");
  ExpectReadError("nomesh.gltf", "{\"asset\": {\"version\": \"2.0\"}}", "no faces");
}

TEST(BadInput, CorruptAndTruncatedGzip) {
  const std::vector<uint8_t> gz = testing::Gzip(ToBytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ExpectReadError("trunc.obj.gz", std::vector<uint8_t>(gz.begin(), gz.end() - 12), "gzip");
  std::vector<uint8_t> corrupt = gz;
  corrupt[12] ^= 0xff;
  corrupt[13] ^= 0x55;
  ExpectReadError("corrupt.obj.gz", corrupt, "gzip");
}

TEST(BadInput, GzipBombIsCapped) {
  const std::vector<uint8_t> zeros(4 << 20, 0);
  const std::vector<uint8_t> gz = testing::Gzip(zeros);
  auto small = InflateGzip(gz.data(), gz.size(), 1 << 20, "bomb.gz");
  ASSERT_FALSE(small.ok());
  EXPECT_EQ(small.status().code(), StatusCode::kResourceLimit);
  auto fits = InflateGzip(gz.data(), gz.size(), 4 << 20, "bomb.gz");
  ASSERT_TRUE(fits.ok()) << fits.status().ToString();
  EXPECT_EQ(fits->size(), zeros.size());
}

TEST(BadInput, RandomMutationsNeverCrash) {
  // Byte flips of valid files in each format: any outcome but a crash is fine.
  const std::vector<std::pair<std::string, std::string>> seeds = {
      {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\nf -1 -2 -3\n"},
      {"off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n"},
      {"ply", std::string(kPlyHeader3) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
  };
  std::mt19937 rng(3);
  for (const auto& [format, text] : seeds) {
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<uint8_t> bytes = ToBytes(text);
      for (int k = 0; k < 3; ++k) bytes[rng() % bytes.size()] = static_cast<uint8_t>(rng());
      auto m = ReadMeshFromBytes(bytes, format, "mutant." + format);
      if (!m.ok()) {
        EXPECT_NE(m.status().message().find("mutant"), std::string::npos);
      }
    }
  }
}

}  // namespace
}  // namespace eqmesh

// The C API (include/eqmesh/eqmesh.h): the same geometry as the C++ decoder, the
// options' level choice, progressive feeding, TEXCOORD_0 from an atlas, and errors
// as codes with messages.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "codec/codec_fixtures.h"
#include "coding/atlas/attach_atlas.h"
#include "coding/decoder.h"
#include "eqmesh/eqmesh.h"
#include "texture/atlas_builder.h"

namespace eqmesh {
namespace {

std::vector<uint8_t> Stream() {
  auto s = Encode(testing::MakeBumpySphereWithKept(3), testing::GoldenOptions());
  EXPECT_TRUE(s.ok());
  return *s;
}

TEST(CApi, DecodesTheSameGeometryAsTheCppDecoder) {
  const std::vector<uint8_t> stream = Stream();
  eqmesh_mesh mesh;
  char error[256];
  ASSERT_EQ(eqmesh_decode(stream.data(), stream.size(), nullptr, &mesh, error, sizeof error), 0) << error;
  auto cpp = Decode(stream.data(), stream.size());
  ASSERT_TRUE(cpp.ok());
  ASSERT_EQ(mesh.vertex_count, cpp->positions.size());
  ASSERT_EQ(mesh.triangle_count, cpp->faces.size());
  EXPECT_EQ(mesh.level, 3);
  EXPECT_EQ(mesh.levels, 3);
  EXPECT_EQ(mesh.texcoords, nullptr);
  for (size_t i = 0; i < cpp->positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.positions[3 * i + c], static_cast<float>(cpp->positions[i][c]));
    const double n = std::sqrt(mesh.normals[3 * i] * mesh.normals[3 * i] + mesh.normals[3 * i + 1] * mesh.normals[3 * i + 1] +
                               mesh.normals[3 * i + 2] * mesh.normals[3 * i + 2]);
    EXPECT_NEAR(n, 1.0, 1e-6);
  }
  for (size_t f = 0; f < cpp->faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.indices[3 * f + c], cpp->faces[f][c]);
  }
  eqmesh_mesh_free(&mesh);
  EXPECT_EQ(mesh.positions, nullptr);
  eqmesh_mesh_free(&mesh);  // safe on a freed mesh
}

TEST(CApi, OptionsChooseTheFinestLevelWithinTheLimits) {
  const std::vector<uint8_t> stream = Stream();
  eqmesh_decode_options options;
  eqmesh_decode_options_init(&options);
  options.max_level = 1;
  eqmesh_mesh mesh;
  ASSERT_EQ(eqmesh_decode(stream.data(), stream.size(), &options, &mesh, nullptr, 0), 0);
  EXPECT_EQ(mesh.level, 1);
  const uint32_t level1 = mesh.triangle_count;  // 20 * 4 + 4 kept
  EXPECT_EQ(level1, 84u);
  eqmesh_mesh_free(&mesh);
  eqmesh_decode_options_init(&options);
  options.max_triangles = 400;  // level 2 has 324, level 3 1284: an adaptive cut between them
  ASSERT_EQ(eqmesh_decode(stream.data(), stream.size(), &options, &mesh, nullptr, 0), 0);
  EXPECT_LE(mesh.triangle_count, 400u);
  EXPECT_GT(mesh.triangle_count, 324u);
  eqmesh_mesh_free(&mesh);
  options.max_triangles = 1;  // nothing fits: the base
  ASSERT_EQ(eqmesh_decode(stream.data(), stream.size(), &options, &mesh, nullptr, 0), 0);
  EXPECT_EQ(mesh.triangle_count, 24u);  // the 20 base faces and the kept tetrahedron
  eqmesh_mesh_free(&mesh);
}

TEST(CApi, BadInputGivesACodeAndAMessage) {
  const std::vector<uint8_t> stream = Stream();
  eqmesh_mesh mesh;
  char error[64];
  const uint8_t junk[16] = {1, 2, 3};
  EXPECT_EQ(eqmesh_decode(junk, sizeof junk, nullptr, &mesh, error, sizeof error), 5);
  EXPECT_NE(std::string(error).find("bad magic"), std::string::npos) << error;
  EXPECT_EQ(mesh.positions, nullptr);
  // A cut stream without a level limit is an error (with one, its complete levels decode).
  EXPECT_EQ(eqmesh_decode(stream.data(), stream.size() - 1, nullptr, &mesh, error, sizeof error), 5);
  EXPECT_EQ(eqmesh_decode(stream.data(), stream.size(), nullptr, nullptr, error, sizeof error), 3);
  char tiny[8];
  EXPECT_EQ(eqmesh_decode(junk, sizeof junk, nullptr, &mesh, tiny, sizeof tiny), 5);
  EXPECT_EQ(std::strlen(tiny), 7u);  // truncated to fit, NUL-terminated
  for (size_t cut = 0; cut < stream.size(); cut += 7) {
    std::vector<uint8_t> damaged = stream;
    damaged[cut] ^= 0x5A;
    if (eqmesh_decode(damaged.data(), damaged.size(), nullptr, &mesh, error, sizeof error) == 0) eqmesh_mesh_free(&mesh);
  }
}

TEST(CApi, ProgressiveFeedingReachesEveryLevelAsItsBytesArrive) {
  const std::vector<uint8_t> stream = Stream();
  auto info = ReadStreamInfo(stream.data(), stream.size());
  ASSERT_TRUE(info.ok());
  eqmesh_progressive* p = eqmesh_progressive_create(nullptr);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(eqmesh_progressive_level(p), -1);
  int last = -1;
  char error[256];
  for (size_t at = 0; at < stream.size(); at += 50) {
    const size_t n = std::min<size_t>(50, stream.size() - at);
    ASSERT_EQ(eqmesh_progressive_feed(p, stream.data() + at, n, error, sizeof error), 0) << error;
    const int level = eqmesh_progressive_level(p);
    EXPECT_GE(level, last);
    for (int k = 0; k <= static_cast<int>(info->levels); ++k) {
      EXPECT_EQ(level >= k, at + n >= info->prefix_size[static_cast<size_t>(k)]) << at << " " << k;
    }
    if (level > last) {
      eqmesh_mesh mesh;
      ASSERT_EQ(eqmesh_progressive_decode(p, level, &mesh, error, sizeof error), 0) << error;
      EXPECT_EQ(mesh.level, level);
      eqmesh_mesh_free(&mesh);
    }
    last = level;
  }
  EXPECT_EQ(last, 3);
  eqmesh_mesh mesh;
  EXPECT_EQ(eqmesh_progressive_decode(p, 4, &mesh, error, sizeof error), 3);
  EXPECT_NE(eqmesh_progressive_feed(p, stream.data(), 1, error, sizeof error), 0);  // past the end
  eqmesh_progressive_destroy(p);
  eqmesh_progressive* bad = eqmesh_progressive_create(nullptr);
  const uint8_t junk[4] = {'N', 'O', 'P', 'E'};
  EXPECT_EQ(eqmesh_progressive_feed(bad, junk, sizeof junk, error, sizeof error), 5);
  eqmesh_progressive_destroy(bad);
}

TEST(CApi, AStreamWithAnAtlasGivesTexcoords) {
  const std::vector<uint8_t> plain = Stream();
  auto decoded = DecodeSemiRegular(plain.data(), plain.size());
  ASSERT_TRUE(decoded.ok());
  auto atlas = texture::BuildAtlas(*decoded, {256, 256, 2});
  ASSERT_TRUE(atlas.ok());
  auto stream = AttachAtlas(plain, *atlas);
  ASSERT_TRUE(stream.ok());
  eqmesh_mesh mesh;
  char error[256];
  ASSERT_EQ(eqmesh_decode(stream->data(), stream->size(), nullptr, &mesh, error, sizeof error), 0) << error;
  ASSERT_NE(mesh.texcoords, nullptr);
  EXPECT_GT(mesh.vertex_count, decoded->positions.size());  // split at the atlas seams
  for (uint32_t i = 0; i < 2 * mesh.vertex_count; ++i) EXPECT_TRUE(mesh.texcoords[i] > 0 && mesh.texcoords[i] < 1);
  eqmesh_mesh_free(&mesh);
}

}  // namespace
}  // namespace eqmesh

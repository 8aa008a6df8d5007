// The atlas chunk (coding/atlas/), its layout (texture/atlas_builder) and the
// texture transfer (texture/texture_transfer) on a synthetic bumpy sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "codec/codec_fixtures.h"
#include "coding/atlas/attach_atlas.h"
#include "coding/atlas/seam_split.h"
#include "coding/decoder.h"
#include "coding/stream_header.h"
#include "texture/atlas_builder.h"
#include "texture/tangent_frames.h"
#include "texture/texture_transfer.h"

namespace eqmesh {
namespace {

struct Fixture {
  std::vector<uint8_t> plain;     // stream without atlas
  std::vector<uint8_t> textured;  // the same with one
  SemiRegularMesh decoded;
  AtlasLayout atlas;
};

Fixture MakeFixture() {
  Fixture f;
  auto stream = Encode(testing::MakeBumpySphereWithKept(3), testing::GoldenOptions());
  EXPECT_TRUE(stream.ok()) << stream.status().ToString();
  f.plain = *stream;
  auto decoded = DecodeSemiRegular(f.plain.data(), f.plain.size());
  EXPECT_TRUE(decoded.ok());
  f.decoded = *decoded;
  auto atlas = texture::BuildAtlas(f.decoded, {256, 256, 2});
  EXPECT_TRUE(atlas.ok()) << atlas.status().ToString();
  f.atlas = *atlas;
  auto textured = AttachAtlas(f.plain, f.atlas);
  EXPECT_TRUE(textured.ok()) << textured.status().ToString();
  f.textured = *textured;
  return f;
}

bool SameCells(const AtlasLayout& a, const AtlasLayout& b) {
  if (a.width != b.width || a.height != b.height || a.gutter != b.gutter || a.cells.size() != b.cells.size()) return false;
  for (size_t i = 0; i < a.cells.size(); ++i) {
    const AtlasCell &x = a.cells[i], &y = b.cells[i];
    if (x.face_a != y.face_a || x.paired != y.paired || (x.paired && x.face_b != y.face_b) || x.edge != y.edge ||
        x.x != y.x || x.y != y.y || x.side != y.side) {
      return false;
    }
  }
  return true;
}

TEST(AtlasChunk, JoinsTheStreamWithoutChangingItsGeometry) {
  const Fixture f = MakeFixture();
  // The atlas asks for 1.4 and leaves a stream that needs more (compact chunks in the
  // positions-after layout, 1.6) as it is.
  const uint8_t flags = f.plain[9];
  const bool positions_after = (flags & bitstream::kCompactPositionsAfter) != 0;
  const bool compact_kept = (flags & bitstream::kCompactKept) != 0;
  EXPECT_EQ(f.plain[5], positions_after ? bitstream::kVersionMinorPositionsAfter
                        : compact_kept  ? bitstream::kVersionMinorCompactKept
                                        : bitstream::kVersionMinorWithoutAtlas);
  EXPECT_EQ(f.textured[5], std::max(f.plain[5], bitstream::kVersionMinorAtlas));
  auto info = ReadStreamInfo(f.textured.data(), f.textured.size());
  ASSERT_TRUE(info.ok());
  EXPECT_TRUE(info->has_atlas);
  EXPECT_EQ(info->total_size, f.textured.size());
  auto decoded = DecodeSemiRegular(f.textured.data(), f.textured.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->positions, f.decoded.positions);
  auto atlas = DecodeAtlas(f.textured.data(), f.textured.size(), *decoded);
  ASSERT_TRUE(atlas.ok()) << atlas.status().ToString();
  ASSERT_TRUE(atlas->has_value());
  EXPECT_TRUE(SameCells(**atlas, f.atlas));
  auto none = DecodeAtlas(f.plain.data(), f.plain.size(), f.decoded);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  // Every prefix that reaches level 0 carries the atlas.
  EXPECT_GE(info->prefix_size[0], info->atlas_offset + info->atlas_size);
}

TEST(AtlasChunk, EveryFaceGetsOneCellAndCellsDoNotOverlap) {
  const Fixture f = MakeFixture();
  const size_t faces = AtlasFaces(f.decoded).size();
  std::vector<int> seen(faces, 0);
  for (const AtlasCell& c : f.atlas.cells) {
    ++seen[c.face_a];
    if (c.paired) ++seen[c.face_b];
    EXPECT_LE(c.x + c.side, f.atlas.width);
    EXPECT_LE(c.y + c.side, f.atlas.height);
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  size_t paired = 0;
  for (size_t i = 0; i < f.atlas.cells.size(); ++i) {
    const AtlasCell& a = f.atlas.cells[i];
    paired += a.paired;
    for (size_t j = i + 1; j < f.atlas.cells.size(); ++j) {
      const AtlasCell& b = f.atlas.cells[j];
      const bool apart = a.x + a.side <= b.x || b.x + b.side <= a.x || a.y + a.side <= b.y || b.y + b.side <= a.y;
      EXPECT_TRUE(apart) << i << " " << j;
    }
  }
  EXPECT_GT(paired * 2, faces * 3 / 4);  // the icosahedron pairs (nearly) all its faces
}

TEST(AtlasChunk, DamagedChunksAreRefusedOrReadConsistently) {
  const Fixture f = MakeFixture();
  auto info = ReadStreamInfo(f.textured.data(), f.textured.size());
  ASSERT_TRUE(info.ok());
  const std::vector<Face> faces = AtlasFaces(f.decoded);
  const uint8_t* chunk = f.textured.data() + info->atlas_offset;
  const size_t size = static_cast<size_t>(info->atlas_size);
  for (size_t n = 0; n < size; ++n) EXPECT_FALSE(ReadAtlasChunk(chunk, n, faces).ok()) << n;
  for (size_t i = 0; i < size; ++i) {
    for (const int flip : {0x01, 0x80, 0xFF}) {
      std::vector<uint8_t> bad(chunk, chunk + size);
      bad[i] = static_cast<uint8_t>(bad[i] ^ flip);
      auto atlas = ReadAtlasChunk(bad.data(), bad.size(), faces);
      if (!atlas.ok()) continue;
      // A chunk that still reads gives every face a texture triangle inside the grid.
      for (const FaceTexCoords& t : FaceCornerTexCoords(*atlas, faces)) {
        for (const TexCoord& uv : t) EXPECT_TRUE(uv[0] >= 0 && uv[0] <= 1 && uv[1] >= 0 && uv[1] <= 1);
      }
    }
  }
  AtlasLayout twice = f.atlas;
  twice.cells[1].face_a = twice.cells[0].face_a;
  const std::vector<uint8_t> bytes = WriteAtlasChunk(twice);
  auto refused = ReadAtlasChunk(bytes.data(), bytes.size(), faces);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("placed twice"), std::string::npos) << refused.status().message();
}

double SignedUvArea(const FaceTexCoords& t) {
  return (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]);
}

TEST(SeamSplit, PositionsStayWeldedAndEveryTriangleStaysInItsCell) {
  const Fixture f = MakeFixture();
  const std::vector<FaceTexCoords> corners = FaceCornerTexCoords(f.atlas, AtlasFaces(f.decoded));
  for (int level = 0; level <= f.decoded.hierarchy.levels(); ++level) {
    const Mesh welded = ExtractLevel(f.decoded, level);
    const SeamSplitMesh split = SplitLevelAtSeams(f.decoded, level, corners);
    ASSERT_EQ(split.faces.size(), welded.faces.size());
    ASSERT_EQ(split.texcoords.size(), split.source_vertex.size());
    EXPECT_GT(split.source_vertex.size(), welded.positions.size());  // base vertices are seams
    for (size_t i = 0; i < welded.positions.size(); ++i) EXPECT_EQ(split.source_vertex[i], i);
    for (size_t t = 0; t < split.faces.size(); ++t) {
      for (size_t k = 0; k < 3; ++k) EXPECT_EQ(split.source_vertex[split.faces[t][k]], welded.faces[t][k]);
    }
    // The same orientation as the base face's texture triangle, never degenerate.
    const std::vector<FaceTexCoords> uvs = LevelCornerTexCoords(f.decoded, level, corners);
    const size_t per_base = f.decoded.hierarchy.Faces(level).size() / f.decoded.hierarchy.BaseFaces().size();
    for (size_t t = 0; t < f.decoded.hierarchy.Faces(level).size(); ++t) {
      const double a = SignedUvArea(uvs[t]), base = SignedUvArea(corners[t / per_base]);
      EXPECT_GT(a * base, 0.0) << t;
      EXPECT_NEAR(a, base / static_cast<double>(per_base), 1e-12);
    }
  }
}

// Input texture: a smooth colour ramp over a planar projection of the surface; the
// painted atlas, sampled at each decoded vertex's TEXCOORD_0, must give the colour
// the input gives at that point.
TEST(TextureTransfer, PaintedAtlasReproducesTheInputColourAtEveryVertex) {
  const Fixture f = MakeFixture();
  const Mesh input = ExtractLevel(f.decoded, f.decoded.hierarchy.levels());
  std::vector<std::array<double, 2>> input_uv;
  for (const Vec3& p : input.positions) input_uv.push_back({0.5 + 0.4 * p.x(), 0.5 + 0.4 * p.y()});
  texture::Image ramp;
  ramp.width = ramp.height = 256;
  ramp.channels = 3;
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      ramp.pixels.insert(ramp.pixels.end(), {static_cast<uint8_t>(x), static_cast<uint8_t>(y), uint8_t{128}});
    }
  }
  const texture::TexturedInput textured{&input, &input_uv};
  auto map = texture::MapAtlasTexels(f.decoded, f.atlas, textured, 256, 256);
  ASSERT_TRUE(map.ok()) << map.status().ToString();
  texture::SourceTexture source;
  source.image = &ramp;
  source.wrap_s = source.wrap_t = 33071;  // CLAMP_TO_EDGE
  const texture::Image painted = texture::PaintAtlas(*map, textured, source);
  ASSERT_EQ(painted.channels, 3);
  const std::vector<FaceTexCoords> corners = FaceCornerTexCoords(f.atlas, AtlasFaces(f.decoded));
  const SeamSplitMesh split = SplitLevelAtSeams(f.decoded, f.decoded.hierarchy.levels(), corners);
  double worst = 0, sum = 0;
  for (size_t i = 0; i < split.source_vertex.size(); ++i) {
    const int x = std::clamp(static_cast<int>(split.texcoords[i][0] * 256), 0, 255);
    const int y = std::clamp(static_cast<int>(split.texcoords[i][1] * 256), 0, 255);
    const Vec3& p = input.positions[split.source_vertex[i]];
    // The kept tetrahedron (x = 2) lies past the ramp's edge: CLAMP_TO_EDGE.
    const double expected_r = std::clamp((0.5 + 0.4 * p.x()) * 256 - 0.5, 0.0, 255.0);
    const double error = std::abs(painted.pixels[(static_cast<size_t>(y) * 256 + static_cast<size_t>(x)) * 3] - expected_r);
    worst = std::max(worst, error);
    sum += error;
  }
  EXPECT_LT(sum / static_cast<double>(split.source_vertex.size()), 2.0);
  EXPECT_LT(worst, 6.0);
}

// A tangent-space normal map moves to the atlas: the object-space normal it gives
// with the decoded surface's frames matches the one the input map gives with the
// input's frames (where the input's planar projection is well conditioned).
TEST(TextureTransfer, NormalMapKeepsItsObjectSpaceNormals) {
  const Fixture f = MakeFixture();
  const Mesh input = ExtractLevel(f.decoded, f.decoded.hierarchy.levels());
  std::vector<std::array<double, 2>> input_uv;
  for (const Vec3& p : input.positions) input_uv.push_back({0.5 + 0.4 * p.x(), 0.5 + 0.4 * p.y()});
  std::vector<Vec3> input_normals = VertexNormals(input);
  for (Vec3& n : input_normals) n.normalize();
  const std::vector<texture::Vec4> input_tangents = texture::VertexTangents(input, input_uv, input_normals);
  const Vec3 tilt = Vec3(0.3, -0.2, 0.9).normalized();  // the map's constant tangent-space normal
  texture::Image map;
  map.width = map.height = 64;
  map.channels = 3;
  for (int i = 0; i < 64 * 64; ++i) {
    for (int c = 0; c < 3; ++c) map.pixels.push_back(static_cast<uint8_t>(std::lround((tilt[c] + 1) * 127.5)));
  }
  // The decoded side as the loader writes it: split at the atlas seams.
  const std::vector<FaceTexCoords> corners = FaceCornerTexCoords(f.atlas, AtlasFaces(f.decoded));
  const SeamSplitMesh split = SplitLevelAtSeams(f.decoded, f.decoded.hierarchy.levels(), corners);
  Mesh decoded;
  for (uint32_t v : split.source_vertex) decoded.positions.push_back(input.positions[v]);
  decoded.faces = split.faces;
  std::vector<Vec3> decoded_normals;
  for (uint32_t v : split.source_vertex) decoded_normals.push_back(input_normals[v]);
  std::vector<std::array<double, 2>> decoded_uv;
  for (const auto& t : split.texcoords) decoded_uv.push_back({t[0], t[1]});
  const std::vector<texture::Vec4> decoded_tangents = texture::VertexTangents(decoded, decoded_uv, decoded_normals);

  const texture::TexturedInput textured{&input, &input_uv};
  auto texels = texture::MapAtlasTexels(f.decoded, f.atlas, textured, 256, 256);
  ASSERT_TRUE(texels.ok());
  const texture::NormalMapFrames frames{&input_tangents, &input_normals, &decoded, &decoded_tangents, &decoded_normals, 1.0};
  texture::SourceTexture source;
  source.image = &map;
  source.normal_map = &frames;
  const texture::Image painted = texture::PaintAtlas(*texels, textured, source);

  double worst = 0, sum = 0;
  int checked = 0;
  for (size_t t = 0; t < decoded.faces.size(); ++t) {
    const Vec3 centre = (decoded.positions[decoded.faces[t][0]] + decoded.positions[decoded.faces[t][1]] +
                         decoded.positions[decoded.faces[t][2]]) / 3.0;
    if (centre.z() < 0.5 || centre.norm() > 1.5) continue;  // the upper cap: planar UVs well conditioned there
    const std::array<float, 3> third{1.0f / 3, 1.0f / 3, 1.0f / 3};
    const texture::Frame in = texture::FrameAt(input, input_tangents, input_normals, static_cast<uint32_t>(t), third);
    const Vec3 expected = (tilt.x() * in.t + tilt.y() * in.b + tilt.z() * in.n).normalized();
    double u = 0, v = 0;
    for (uint32_t k : decoded.faces[t]) {
      u += split.texcoords[k][0] / 3.0;
      v += split.texcoords[k][1] / 3.0;
    }
    const size_t x = static_cast<size_t>(std::clamp(static_cast<int>(u * 256), 0, 255));
    const size_t y = static_cast<size_t>(std::clamp(static_cast<int>(v * 256), 0, 255));
    const uint8_t* px = &painted.pixels[(y * 256 + x) * 3];
    const Vec3 local(px[0] / 127.5 - 1, px[1] / 127.5 - 1, px[2] / 127.5 - 1);
    const texture::Frame out = texture::FrameAt(decoded, decoded_tangents, decoded_normals, static_cast<uint32_t>(t), third);
    const Vec3 got = (local.x() * out.t + local.y() * out.b + local.z() * out.n).normalized();
    const double degrees = std::acos(std::clamp(got.dot(expected), -1.0, 1.0)) * 180.0 / 3.14159265358979;
    worst = std::max(worst, degrees);
    sum += degrees;
    ++checked;
  }
  ASSERT_GT(checked, 100);
  EXPECT_LT(sum / checked, 2.0);
  EXPECT_LT(worst, 10.0);
}

}  // namespace
}  // namespace eqmesh

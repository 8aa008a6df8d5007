// Crease tags in the stream (1.8, crease_chunk.h): they travel, the decoder's
// stencils follow them as the encoder's did, and a cube coded with its edges
// tagged costs a fraction of the same cube untagged.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "codec_fixtures.h"
#include "coding/crease_chunk.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "coding/stream_header.h"
#include "mesh_io/semi_regular_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

using bitstream::CoderId;
using bitstream::TransformId;

// The positions of the tagged base edges' ends, each edge's pair sorted: the
// decoder numbers base vertices in its own order.
std::vector<std::pair<std::vector<double>, std::vector<double>>> TaggedEnds(const SemiRegularMesh& m) {
  std::vector<std::pair<std::vector<double>, std::vector<double>>> out;
  for (const Edge& e : m.hierarchy.BaseCreases()) {
    std::vector<double> a(m.positions[e[0]].data(), m.positions[e[0]].data() + 3);
    std::vector<double> b(m.positions[e[1]].data(), m.positions[e[1]].data() + 3);
    if (b < a) std::swap(a, b);
    out.emplace_back(a, b);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The cube refined four times at its edges' midpoints (the cube itself).
SemiRegularMesh RefinedCube(bool tagged) {
  const testing::CubeWithEdges cube = testing::MakeCube();
  SemiRegularMesh mesh;
  mesh.hierarchy = SemiRegularHierarchy::Build(8, cube.mesh.faces, 4).value();
  if (tagged) {
    EXPECT_TRUE(mesh.hierarchy.SetBaseCreases(cube.edges).ok());
  }
  mesh.positions = cube.mesh.positions;
  for (int j = 0; j < 4; ++j) {
    for (const Edge& e : mesh.hierarchy.OddEdges(j)) {
      mesh.positions.push_back(0.5 * (mesh.positions[e[0]] + mesh.positions[e[1]]));
    }
  }
  return mesh;
}

class CreaseStream : public ::testing::TestWithParam<CoderId> {};

TEST_P(CreaseStream, TagsTravelAndTheStreamDecodesDeterministically) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithCreases(3);
  EncodeOptions options;
  options.coder = GetParam();
  options.lambda = 0.05;
  auto bytes = Encode(mesh, options);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  EXPECT_EQ(*bytes, Encode(mesh, options).value());
  const StreamInfo info = ReadStreamInfo(bytes->data(), bytes->size()).value();
  EXPECT_TRUE(info.has_creases);
  EXPECT_EQ(info.version_minor, bitstream::kVersionMinorCreaseEdges);
  auto decoded = DecodeSemiRegular(bytes->data(), bytes->size(), {});
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  // The same three edges, by their (quantized) ends.
  ASSERT_EQ(decoded->hierarchy.BaseCreases().size(), 3u);
  const auto want = TaggedEnds(mesh), got = TaggedEnds(*decoded);
  for (size_t i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(want[i].first[c], got[i].first[c], 1e-3);
      EXPECT_NEAR(want[i].second[c], got[i].second[c], 1e-3);
    }
  }
  EXPECT_LE(testing::MaxNearestDistance(decoded->positions, mesh.positions), 0.05);
}

INSTANTIATE_TEST_SUITE_P(Coders, CreaseStream, ::testing::Values(CoderId::kEq, CoderId::kZerotree));

TEST(CreaseStream, ACubeWithItsEdgesTaggedCostsAFractionOfTheUntaggedCube) {
  EncodeOptions options;
  options.lambda = 0.05;
  size_t bytes[2] = {0, 0};
  for (const bool tagged : {false, true}) {
    const SemiRegularMesh cube = RefinedCube(tagged);
    auto stream = Encode(cube, options);
    ASSERT_TRUE(stream.ok()) << stream.status().ToString();
    bytes[tagged] = stream->size();
    auto decoded = Decode(stream->data(), stream->size());
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    if (tagged) {
      EXPECT_LE(testing::MaxNearestDistance(decoded->positions, cube.positions), 1e-3);
    }
  }
  // Untagged, every level codes the rounding the butterfly gives the cube's
  // edges; tagged, the prediction is the cube.
  EXPECT_LT(2 * bytes[1], bytes[0]) << bytes[1] << " tagged against " << bytes[0] << " untagged";
}

TEST(CreaseStream, AStreamWithoutTagsHasNoCreaseChunkAndKeepsItsVersion) {
  EncodeOptions options;
  options.lambda = 0.05;
  const std::vector<uint8_t> bytes = Encode(testing::MakeBumpySphere(2), options).value();
  const StreamInfo info = ReadStreamInfo(bytes.data(), bytes.size()).value();
  EXPECT_FALSE(info.has_creases);
  EXPECT_LT(info.version_minor, bitstream::kVersionMinorCreaseEdges);
}

TEST(CreaseStream, TheCreaseFlagWithoutLevelsIsCorrupt) {
  StreamHeader h;
  h.flags = bitstream::kCreaseEdges;
  h.crease_size = 4;
  h.base_size = 10;
  const std::vector<uint8_t> header = WriteStreamHeader(h);
  size_t size = 0;
  auto read = ReadStreamHeader(header.data(), header.size(), &size);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), StatusCode::kCorruptStream);
}

TEST(CreaseStream, AChunkTaggingNothingOrCutShortIsCorrupt) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithCreases(1);
  const std::vector<uint8_t> chunk = WriteCreaseChunk(mesh.hierarchy);
  auto tags = ReadCreaseChunk(chunk.data(), chunk.size(), mesh.hierarchy);
  ASSERT_TRUE(tags.ok()) << tags.status().ToString();
  EXPECT_EQ(tags->size(), 3u);
  for (size_t cut = 0; cut < chunk.size(); ++cut) {
    auto shorter = ReadCreaseChunk(chunk.data(), cut, mesh.hierarchy);
    EXPECT_FALSE(shorter.ok()) << cut << " of " << chunk.size() << " bytes";
  }
  const std::vector<uint8_t> zeros(chunk.size(), 0);
  auto none = ReadCreaseChunk(zeros.data(), zeros.size(), mesh.hierarchy);
  EXPECT_FALSE(none.ok());
}

TEST(CreaseStream, SemiRegularFilesKeepTheTags) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithCreases(2);
  const std::string path = ::testing::TempDir() + "/creases.srm";
  ASSERT_TRUE(WriteSemiRegular(mesh, path).ok());
  auto read = ReadSemiRegular(path);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->hierarchy.BaseCreases(), mesh.hierarchy.BaseCreases());
  EXPECT_EQ(read->positions, mesh.positions);
}

}  // namespace
}  // namespace eqmesh

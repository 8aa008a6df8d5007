// Byte I/O, header, base-mesh chunk and renumbering.
#include <gtest/gtest.h>

#include <set>

#include "codec_fixtures.h"
#include "coding/base_mesh_decoder.h"
#include "coding/base_mesh_encoder.h"
#include "coding/entropy/byte_io.h"
#include "coding/semi_regular_reorder.h"
#include "coding/stream_header.h"
#include "test_support.h"

namespace eqmesh {
namespace {

TEST(ByteIo, VarintsRoundTripAndRejectOverlong) {
  ByteWriter w;
  const uint64_t values[] = {0, 1, 127, 128, 300, 1ull << 35, ~0ull};
  for (uint64_t v : values) w.PutVarint(v);
  w.PutSignedVarint(-5);
  w.PutSignedVarint(INT64_MIN);
  ByteReader r(w.bytes().data(), w.size(), "test");
  for (uint64_t v : values) {
    uint64_t got = 0;
    ASSERT_TRUE(r.ReadVarint(&got).ok());
    EXPECT_EQ(got, v);
    EXPECT_EQ(VarintSize(v), VarintSize(got));
  }
  int64_t s = 0;
  ASSERT_TRUE(r.ReadSignedVarint(&s).ok());
  EXPECT_EQ(s, -5);
  ASSERT_TRUE(r.ReadSignedVarint(&s).ok());
  EXPECT_EQ(s, INT64_MIN);
  EXPECT_EQ(r.remaining(), 0u);
  uint8_t byte = 0;
  EXPECT_EQ(r.ReadU8(&byte).code(), StatusCode::kCorruptStream);

  const std::vector<uint8_t> overlong(11, 0x80);
  ByteReader bad(overlong.data(), overlong.size(), "test");
  uint64_t v = 0;
  EXPECT_EQ(bad.ReadVarint(&v).code(), StatusCode::kCorruptStream);
  const uint8_t too_big[] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02};
  ByteReader bad2(too_big, sizeof too_big, "test");
  EXPECT_EQ(bad2.ReadVarint(&v).code(), StatusCode::kCorruptStream);
  // 5 written in two bytes (0x85 0x00) and in three: overlong, corrupt (spec A.1);
  // 0 as the single byte 0x00 stays valid.
  for (const std::vector<uint8_t>& padded : {std::vector<uint8_t>{0x85, 0x00}, std::vector<uint8_t>{0x85, 0x80, 0x00}}) {
    ByteReader r2(padded.data(), padded.size(), "test");
    EXPECT_EQ(r2.ReadVarint(&v).code(), StatusCode::kCorruptStream);
  }
  const uint8_t zero[] = {0x00};
  ByteReader r3(zero, 1, "test");
  ASSERT_TRUE(r3.ReadVarint(&v).ok());
  EXPECT_EQ(v, 0u);
}

TEST(ByteIo, SpanAndBoundedReadsCheckLength) {
  const uint8_t data[] = {0x05, 1, 2};
  ByteReader r(data, sizeof data, "test");
  uint64_t n = 0;
  EXPECT_FALSE(r.ReadBoundedVarint(4, "count", &n).ok());
  ASSERT_TRUE(r.ReadBoundedVarint(5, "count", &n).ok());
  const uint8_t* span = nullptr;
  EXPECT_FALSE(r.ReadSpan(n, &span).ok());
  EXPECT_TRUE(r.ReadSpan(2, &span).ok());
}

StreamHeader SampleHeader() {
  StreamHeader h;
  h.transform = bitstream::TransformId::kLifted;
  h.levels = 3;
  h.flags = bitstream::kHasKeptExactly;
  h.lambda_code = -37;
  h.tangential_code = LogCode(100.0);
  h.quantum = 1.5e-5f;
  h.base_size = 200;
  h.kept_size = 40;
  h.level_sizes = {10, 300, 4000};
  return h;
}

TEST(StreamHeader, RoundTrips) {
  const StreamHeader h = SampleHeader();
  const std::vector<uint8_t> bytes = WriteStreamHeader(h);
  size_t size = 0;
  auto back = ReadStreamHeader(bytes.data(), bytes.size(), &size);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(size, bytes.size());
  EXPECT_EQ(back->transform, h.transform);
  EXPECT_EQ(back->levels, 3);
  EXPECT_EQ(back->lambda_code, -37);
  EXPECT_NEAR(back->tangential_factor(), 100.0, 3.0);
  EXPECT_EQ(back->quantum, h.quantum);
  EXPECT_EQ(back->kept_size, 40u);
  EXPECT_EQ(back->level_sizes, h.level_sizes);
}

TEST(StreamHeader, RejectsBadMagicVersionCoderAndFlags) {
  const std::vector<uint8_t> good = WriteStreamHeader(SampleHeader());
  size_t size = 0;
  auto with = [&](size_t at, uint8_t value) {
    std::vector<uint8_t> b = good;
    b[at] = value;
    return ReadStreamHeader(b.data(), b.size(), &size).status().code();
  };
  EXPECT_EQ(with(0, 'X'), StatusCode::kCorruptStream);
  EXPECT_EQ(with(4, bitstream::kVersionMajor + 1), StatusCode::kUnsupportedVersion);
  EXPECT_EQ(with(5, 99), StatusCode::kOk);  // newer minor: readable
  // Ids a later minor version may add (ext_spec A.5).
  EXPECT_EQ(with(6, 7), StatusCode::kUnsupportedFeature);   // transform
  // Zerotree (coder 1) carries one embedded payload: chunks 1.. must be empty.
  EXPECT_EQ(with(7, 1), StatusCode::kCorruptStream);
  EXPECT_EQ(with(7, 9), StatusCode::kUnsupportedFeature);
  EXPECT_EQ(with(8, bitstream::kMaxLevels + 1), StatusCode::kCorruptStream);
  // Every bit of the flags byte is defined since 1.8; bit 7 (kCreaseEdges) adds
  // a crease chunk size to the header (below).
  for (size_t n = 0; n < good.size(); ++n) {
    EXPECT_FALSE(ReadStreamHeader(good.data(), n, &size).ok()) << n;
  }
}

TEST(StreamHeader, CreaseChunkSizeRoundTrips) {
  StreamHeader h = SampleHeader();
  h.flags |= bitstream::kCreaseEdges;
  h.crease_size = 23;
  const std::vector<uint8_t> b = WriteStreamHeader(h);
  size_t size = 0;
  auto read = ReadStreamHeader(b.data(), b.size(), &size);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->crease_size, 23u);
  EXPECT_EQ(read->level_sizes, h.level_sizes);
  h.crease_size = 0;
  const std::vector<uint8_t> empty = WriteStreamHeader(h);
  EXPECT_EQ(ReadStreamHeader(empty.data(), empty.size(), &size).status().code(), StatusCode::kCorruptStream);
}

TEST(StreamHeader, ZerotreeHasOneNonEmptyPayloadChunk) {
  StreamHeader h = SampleHeader();
  h.coder = bitstream::CoderId::kZerotree;
  size_t size = 0;
  h.level_sizes = {4310, 0, 0};
  std::vector<uint8_t> b = WriteStreamHeader(h);
  EXPECT_TRUE(ReadStreamHeader(b.data(), b.size(), &size).ok());
  h.level_sizes = {0, 0, 0};
  b = WriteStreamHeader(h);
  EXPECT_EQ(ReadStreamHeader(b.data(), b.size(), &size).status().code(), StatusCode::kCorruptStream);
}

TEST(BaseMesh, DracoRoundTripGivesPermutationAndBoundedError) {
  const Mesh ico = testing::MakeIcosphere(1);
  auto enc = EncodeMeshWithDraco(ico, 12);
  ASSERT_TRUE(enc.ok()) << enc.status().ToString();
  ASSERT_EQ(enc->decoded.positions.size(), ico.positions.size());
  std::set<uint32_t> seen(enc->decoded_to_input.begin(), enc->decoded_to_input.end());
  EXPECT_EQ(seen.size(), ico.positions.size());
  const double step = 2.0 / 4095.0;
  for (size_t i = 0; i < enc->decoded.positions.size(); ++i) {
    EXPECT_LE((enc->decoded.positions[i] - ico.positions[enc->decoded_to_input[i]]).norm(), step);
  }
  // Faces map back to the input's faces (as sets of vertices).
  std::set<std::set<uint32_t>> input_faces;
  for (const Face& f : ico.faces) input_faces.insert({f[0], f[1], f[2]});
  for (const Face& f : enc->decoded.faces) {
    const auto& m = enc->decoded_to_input;
    EXPECT_TRUE(input_faces.count({m[f[0]], m[f[1]], m[f[2]]}));
  }
  auto dec = DecodeDracoMesh(enc->bytes.data(), enc->bytes.size(), {1000, 1000}, "test");
  ASSERT_TRUE(dec.ok());
  EXPECT_EQ(dec->faces, enc->decoded.faces);
  EXPECT_EQ(DecodeDracoMesh(enc->bytes.data(), enc->bytes.size(), {10, 1000}, "test").status().code(),
            StatusCode::kResourceLimit);
}

TEST(BaseMesh, RateDistortionChoiceMovesWithLambda) {
  const Mesh ico = testing::MakeIcosphere(1);
  const std::vector<double> weights(ico.positions.size(), 100.0);
  BaseRdReport low, high;
  ASSERT_TRUE(EncodeBaseMesh(ico, weights, 1e2, &low).ok());
  ASSERT_TRUE(EncodeBaseMesh(ico, weights, 1e12, &high).ok());
  EXPECT_LT(low.depth, high.depth);
  EXPECT_GE(low.depth, bitstream::kBaseMinBits);
  EXPECT_LE(high.depth, bitstream::kBaseMaxBits);
}

TEST(Renumber, KeepsTheSurface) {
  const SemiRegularMesh mesh = testing::MakeBumpySphere(3);
  auto enc = EncodeMeshWithDraco(ExtractLevel(mesh, 0), 14);
  ASSERT_TRUE(enc.ok());
  auto renumbered = RenumberToBase(mesh, enc->decoded_to_input, enc->decoded.faces);
  ASSERT_TRUE(renumbered.ok()) << renumbered.status().ToString();
  // Same set of triangles (as position triples) at the finest level.
  auto triangles = [](const SemiRegularMesh& m) {
    std::set<std::vector<double>> out;
    for (const Face& f : m.hierarchy.Faces(m.hierarchy.levels())) {
      std::vector<std::vector<double>> corners;
      for (uint32_t v : f) corners.push_back({m.positions[v].x(), m.positions[v].y(), m.positions[v].z()});
      std::sort(corners.begin(), corners.end());
      std::vector<double> flat;
      for (const auto& c : corners) flat.insert(flat.end(), c.begin(), c.end());
      out.insert(flat);
    }
    return out;
  };
  EXPECT_EQ(triangles(mesh), triangles(*renumbered));
}

}  // namespace
}  // namespace eqmesh

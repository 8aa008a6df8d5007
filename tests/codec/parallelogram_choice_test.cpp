// The compact chunk's parallelogram choice and greedy order (compact_positions.h,
// stream 1.7): exact agreement of encoder and decoder, fewer bytes on a creased
// extrusion and on a cylinder's rims, no choice
// outside the positions-after axis grid, decode safety, and a stream that uses it
// says so (version 1.7, flag) while the others keep their versions.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "codec_fixtures.h"
#include "codec/compact_chunk_checks.h"
#include "coding/bitstream_shared.h"
#include "coding/compact_base/compact_base_decoder.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// A toothed wheel extruded in `rings` rings and capped by two fans: every rim vertex
// has one exact parallelogram on its side and one across the rim crease on its cap.
Mesh MakeGear(int teeth = 24, int rings = 6) {
  std::vector<std::pair<double, double>> outline;
  for (int t = 0; t < teeth; ++t) {
    for (const auto& [radius, at] : {std::pair{1.0, 0.0}, {1.2, 0.1}, {1.2, 0.4}, {1.0, 0.5}}) {
      const double a = 2.0 * M_PI * (t + at) / teeth;
      outline.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
  }
  const uint32_t n = static_cast<uint32_t>(outline.size());
  Mesh mesh;
  for (int k = 0; k <= rings; ++k) {
    for (const auto& [x, y] : outline) mesh.positions.emplace_back(x, y, 0.3 * k / rings);
  }
  const auto at = [&](int k, uint32_t i) { return static_cast<uint32_t>(k) * n + i % n; };
  for (int k = 0; k < rings; ++k) {
    for (uint32_t i = 0; i < n; ++i) {
      mesh.faces.push_back({at(k, i), at(k, i + 1), at(k + 1, i + 1)});
      mesh.faces.push_back({at(k, i), at(k + 1, i + 1), at(k + 1, i)});
    }
  }
  const uint32_t bottom = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(0.0, 0.0, 0.0);
  mesh.positions.emplace_back(0.0, 0.0, 0.3);
  for (uint32_t i = 0; i < n; ++i) {
    mesh.faces.push_back({bottom, at(0, i + 1), at(0, i)});
    mesh.faces.push_back({bottom + 1, at(rings, i), at(rings, i + 1)});
  }
  return mesh;
}

TEST(ParallelogramChoice, DecoderRebuildsExactlyWhatTheEncoderReports) {
  const Mesh meshes[] = {MakeGear(), testing::MakeIcosphere(3)};
  for (const Mesh& mesh : meshes) {
    for (const double depth : {8.0, 10.25, 14.0}) {
      auto enc = EncodeCompactBaseVariants(mesh, {{depth, kGridTangentialQuarters, true}});
      ASSERT_TRUE(enc.ok()) << enc.status().ToString();
      const std::vector<uint8_t>& bytes = (*enc)[0].bytes;
      auto dec = DecodeCompactBase(bytes.data(), bytes.size(), 1u << 20, "test");
      ASSERT_TRUE(dec.ok()) << dec.status().ToString();
      EXPECT_EQ(dec->faces, (*enc)[0].decoded.faces);
      EXPECT_EQ(dec->positions, (*enc)[0].decoded.positions);  // bit for bit
    }
  }
}

TEST(ParallelogramChoice, TheSameGridPointsInFewerBytesOnACreasedExtrusion) {
  const Mesh gear = MakeGear();
  for (const double depth : {9.0, 12.0}) {
    auto both = EncodeCompactBaseVariants(gear, {{depth, kGridTangentialQuarters, false},
                                                 {depth, kGridTangentialQuarters, true}});
    ASSERT_TRUE(both.ok()) << both.status().ToString();
    EXPECT_EQ((*both)[0].decoded.positions, (*both)[1].decoded.positions);  // a choice of prediction only
    EXPECT_LT((*both)[1].bytes.size(), 0.7 * static_cast<double>((*both)[0].bytes.size())) << depth << " bits";
  }
}

TEST(ParallelogramChoice, TheGreedyOrderPredictsACylindersRimsAlongItsSide) {
  // Two rings: every side triangle is long and thin, and the traversal reaches
  // the rims through the caps' fans.
  const Mesh cylinder = testing::MakeCappedCylinder(1.0, 3.0, 96, 2);
  auto both = EncodeCompactBaseVariants(cylinder, {{9.0, kGridTangentialQuarters, false},
                                                   {9.0, kGridTangentialQuarters, true}});
  ASSERT_TRUE(both.ok()) << both.status().ToString();
  EXPECT_EQ((*both)[0].decoded.positions, (*both)[1].decoded.positions);
  EXPECT_LT((*both)[1].bytes.size(), 0.5 * static_cast<double>((*both)[0].bytes.size()));
  auto dec = DecodeCompactBase((*both)[1].bytes.data(), (*both)[1].bytes.size(), 1u << 20, "test");
  ASSERT_TRUE(dec.ok()) << dec.status().ToString();
  EXPECT_EQ(dec->positions, (*both)[1].decoded.positions);
}

TEST(ParallelogramChoice, OnlyThePositionsAfterAxisGridHasIt) {
  const Mesh sphere = testing::MakeIcosphere(1);
  EXPECT_FALSE(EncodeCompactBaseVariants(sphere, {{10.0, 8, true}}).ok());
  auto plain = EncodeCompactBaseVariants(sphere, {{10.0, kGridTangentialQuarters, false}});
  auto choice = EncodeCompactBaseVariants(sphere, {{10.0, kGridTangentialQuarters, true}});
  ASSERT_TRUE(plain.ok() && choice.ok());
  // Head: varint 42, varint 80, u8 bits, 4 x f32, then the mode byte.
  const size_t at = 1 + 1 + 1 + 16;
  EXPECT_EQ((*plain)[0].bytes[at], kGridTangentialQuarters);
  EXPECT_EQ((*choice)[0].bytes[at], kGridChoiceModeByte);
}

TEST(ParallelogramChoice, DamagedChunksAreErrorsOrFiniteMeshes) {
  auto enc = EncodeCompactBaseVariants(MakeGear(12, 3), {{10.0, kGridTangentialQuarters, true}});
  ASSERT_TRUE(enc.ok());
  testing::ExpectDamagedCompactChunksSafe((*enc)[0].bytes, 4242);
}

// The as-is representation of the gear takes the choice; its stream says so and
// decodes to what the encoder reports.
TEST(ParallelogramChoice, AStreamThatUsesItIsVersion17WithItsFlag) {
  const Mesh gear = MakeGear();
  SemiRegularMesh as_is;
  as_is.hierarchy =
      SemiRegularHierarchy::Build(static_cast<uint32_t>(gear.positions.size()), gear.faces, 0).value();
  as_is.positions = gear.positions;
  EncodeOptions options = testing::GoldenOptions();
  options.lambda = 1e-4;
  auto bytes = Encode(as_is, options);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  auto info = ReadStreamInfo(bytes->data(), bytes->size());
  ASSERT_TRUE(info.ok()) << info.status().ToString();
  EXPECT_EQ(info->version_minor, bitstream::kVersionMinorParallelogramChoice);
  EXPECT_EQ((*bytes)[info->base_offset + 2 + 2 + 1 + 16], kGridChoiceModeByte);
  auto decoded = Decode(bytes->data(), bytes->size());
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->faces.size(), gear.faces.size());
  EXPECT_LE(testing::MaxNearestDistance(decoded->positions, gear.positions), 0.01 * testing::Diagonal(gear.positions));
  // The flag without a compact base in the positions-after layout is corrupt.
  std::vector<uint8_t> bad = *bytes;
  // Header: magic (4), major, minor, transform, coder, levels, flags.
  bad[9] = static_cast<uint8_t>(bad[9] & ~bitstream::kCompactPositionsAfter);
  auto refused = ReadStreamInfo(bad.data(), bad.size());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kCorruptStream);
}

}  // namespace
}  // namespace eqmesh

// The compact chunk's positions-after layout (coding/compact_base/compact_positions.h):
// exact agreement of encoder and decoder in every layout, depth and tangential
// step; one traversal for many variants gives the same bytes as one each; the
// multi-parallelogram pass beats the interleaved one; surface frames spend fewer
// bits on a smooth surface and keep it near; decode safety of frame chunks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "codec/compact_chunk_checks.h"
#include "coding/compact_base/compact_base_decoder.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "coding/compact_base/compact_positions.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// A sphere with bumps: smooth, curved everywhere.
Mesh BumpySphere(int subdivisions) {
  Mesh m = testing::MakeIcosphere(subdivisions);
  for (Vec3& p : m.positions) p *= 1.0 + 0.08 * std::sin(3.0 * p.x()) * std::cos(2.0 * p.y());
  return m;
}

Mesh SphereAndTorus() {
  return testing::WithComponent(BumpySphere(2), testing::MakeTorus(12, 8), Vec3(3.0, 0.5, 0.0));
}

struct Variant {
  CompactLayout layout;
  double depth;
  int quarters;
};

std::string Name(const Variant& v) {
  return std::string(v.layout == CompactLayout::kInterleaved ? "interleaved" : "after") + " depth " +
         std::to_string(v.depth) + " quarters " + std::to_string(v.quarters);
}

TEST(CompactPositions, DecoderRebuildsExactlyWhatTheEncoderReports) {
  const Mesh meshes[] = {SphereAndTorus(), testing::MakeDisc(6)};
  const Variant variants[] = {{CompactLayout::kInterleaved, 10, 4}, {CompactLayout::kPositionsAfter, 10, 4},
                              {CompactLayout::kPositionsAfter, 8.25, 4}, {CompactLayout::kPositionsAfter, 10.5, 8},
                              {CompactLayout::kPositionsAfter, 14.75, 16}, {CompactLayout::kPositionsAfter, 6, 255}};
  for (const Mesh& mesh : meshes) {
    for (const Variant& v : variants) {
      SCOPED_TRACE(Name(v));
      auto enc = EncodeCompactBase(mesh, v.depth, v.layout, v.quarters);
      ASSERT_TRUE(enc.ok()) << enc.status().ToString();
      auto dec = DecodeCompactBase(enc->bytes.data(), enc->bytes.size(), 1u << 20, "test", v.layout);
      ASSERT_TRUE(dec.ok()) << dec.status().ToString();
      EXPECT_EQ(dec->faces, enc->decoded.faces);
      ASSERT_EQ(dec->positions.size(), mesh.positions.size());
      for (size_t i = 0; i < dec->positions.size(); ++i) {
        ASSERT_EQ(dec->positions[i], enc->decoded.positions[i]) << "vertex " << i;  // bit for bit
      }
      // Every decoded vertex is near the input vertex it came from: within half a
      // tangential step on each frame axis.
      const double step = testing::LargestExtent(mesh) / (std::exp2(v.depth) - 1.0);
      const double bound = 0.5 * std::sqrt(3.0) * step * v.quarters / 4.0 * 1.0001;
      for (size_t i = 0; i < dec->positions.size(); ++i) {
        EXPECT_LE((dec->positions[i] - mesh.positions[enc->decoded_to_input[i]]).norm(), bound) << "vertex " << i;
      }
    }
  }
}

TEST(CompactPositions, OneTraversalForManyVariantsGivesTheSameBytes) {
  const Mesh mesh = SphereAndTorus();
  const std::vector<CompactVariant> variants = {{9.0, 4}, {9.25, 4}, {11.5, 6}, {12.0, 12}};
  auto many = EncodeCompactBaseVariants(mesh, variants);
  ASSERT_TRUE(many.ok()) << many.status().ToString();
  ASSERT_EQ(many->size(), variants.size());
  for (size_t i = 0; i < variants.size(); ++i) {
    auto one = EncodeCompactBase(mesh, variants[i].depth, CompactLayout::kPositionsAfter,
                                 variants[i].tangential_quarters);
    ASSERT_TRUE(one.ok());
    EXPECT_EQ((*many)[i].bytes, one->bytes) << "variant " << i;
    EXPECT_EQ((*many)[i].decoded_to_input, one->decoded_to_input);
  }
}

TEST(CompactPositions, AllParallelogramsPredictBetterThanTheDiscoveringGate) {
  const Mesh mesh = BumpySphere(4);  // 2,562 vertices
  for (const double depth : {10.0, 14.0}) {
    auto interleaved = EncodeCompactBase(mesh, depth, CompactLayout::kInterleaved);
    auto after = EncodeCompactBase(mesh, depth, CompactLayout::kPositionsAfter);
    ASSERT_TRUE(interleaved.ok() && after.ok());
    EXPECT_LT(after->bytes.size(), 0.95 * static_cast<double>(interleaved->bytes.size())) << depth << " bits";
    EXPECT_EQ(after->decoded.positions, interleaved->decoded.positions);  // the same grid points
  }
}

// Radial error of a decoded unit-sphere vertex: its distance from the surface.
double MaxRadialError(const Mesh& decoded) {
  double worst = 0;
  for (const Vec3& p : decoded.positions) worst = std::max(worst, std::abs(p.norm() - 1.0));
  return worst;
}

TEST(CompactPositions, SurfaceFramesSpendFewerBitsOnASmoothSurfaceAndStayOnIt) {
  const Mesh sphere = testing::MakeIcosphere(4);
  const double depth = 10.0;
  const double step = testing::LargestExtent(sphere) / (std::exp2(depth) - 1.0);
  auto grid = EncodeCompactBase(sphere, depth, CompactLayout::kPositionsAfter, 4);
  auto frames = EncodeCompactBase(sphere, depth, CompactLayout::kPositionsAfter, 16);
  ASSERT_TRUE(grid.ok() && frames.ok());
  EXPECT_LT(frames->bytes.size(), 0.8 * static_cast<double>(grid->bytes.size()));
  // Four times the grid step along the surface, yet off it by about what the grid
  // gives: the normal part keeps the grid step.
  EXPECT_LE(MaxRadialError(grid->decoded), 0.87 * step);
  EXPECT_LE(MaxRadialError(frames->decoded), 1.5 * step);
}

TEST(CompactPositions, DamagedFrameChunksAreErrorsOrFiniteMeshes) {
  auto enc = EncodeCompactBase(SphereAndTorus(), 10, CompactLayout::kPositionsAfter, 12);
  ASSERT_TRUE(enc.ok());
  testing::ExpectDamagedCompactChunksSafe(enc->bytes, 777);
}

TEST(CompactPositions, ATangentialStepBelowTheGridStepIsCorrupt) {
  auto enc = EncodeCompactBase(testing::MakeIcosphere(1), 10, CompactLayout::kPositionsAfter, 8);
  ASSERT_TRUE(enc.ok());
  // Head: varint 42, varint 80, u8 bits, 4 x f32, then the tangential byte.
  std::vector<uint8_t> bad = enc->bytes;
  const size_t at = 1 + 1 + 1 + 16;
  ASSERT_EQ(bad[at], 8);
  bad[at] = 3;
  auto dec = DecodeCompactBase(bad.data(), bad.size(), 1u << 20, "test");
  ASSERT_FALSE(dec.ok());
  EXPECT_EQ(dec.status().code(), StatusCode::kCorruptStream);
  EXPECT_NE(dec.status().message().find("tangential step"), std::string::npos) << dec.status().message();
  EXPECT_FALSE(EncodeCompactBase(testing::MakeIcosphere(1), 10, CompactLayout::kInterleaved, 8).ok());
  EXPECT_FALSE(EncodeCompactBase(testing::MakeIcosphere(1), 10, CompactLayout::kPositionsAfter, 3).ok());
}

}  // namespace
}  // namespace eqmesh

// Coder 1 (zerotree) in the container: embedded open-loop encode -> decode, exact
// byte budgets, determinism, prefixes of the embedded payload, --level access.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "coding/zerotree_encoder.h"
#include "metrics/surface_distance.h"

namespace eqmesh {
namespace {

using bitstream::CoderId;
using bitstream::TransformId;

constexpr size_t kInputVertices = 500;

EncodeOptions ZerotreeOptions(TransformId transform, double bpv) {
  EncodeOptions options;
  options.coder = CoderId::kZerotree;
  options.transform = transform;
  options.target_bpv = bpv;
  options.input_vertices = kInputVertices;
  return options;
}

class ZerotreeCodec : public ::testing::TestWithParam<TransformId> {};

TEST_P(ZerotreeCodec, ErrorDecreasesWithTheBudgetAndTheBudgetIsHitExactly) {
  const SemiRegularMesh mesh = testing::MakeBumpySphere(3);
  const double diagonal = testing::Diagonal(mesh.positions);
  double last_error = 1e300;
  for (const double bpv : {4.0, 8.0, 12.0, 18.0}) {  // all between the smallest and the complete stream
    EncodeReport report;
    auto bytes = Encode(mesh, ZerotreeOptions(GetParam(), bpv), &report);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    const double budget = std::floor(bpv * kInputVertices / 8.0);
    EXPECT_LE(static_cast<double>(bytes->size()), budget);
    EXPECT_GE(static_cast<double>(bytes->size()), 0.97 * budget) << bpv;
    ASSERT_EQ(report.level_bytes.size(), 3u);
    EXPECT_GT(report.level_bytes[0], 0u);
    EXPECT_EQ(report.level_bytes[1] + report.level_bytes[2], 0u);  // one embedded payload
    DecodeInfo info;
    auto decoded = Decode(bytes->data(), bytes->size(), {}, &info);
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    EXPECT_EQ(info.levels_decoded, 3);
    ASSERT_EQ(decoded->positions.size(), mesh.positions.size());
    const double error = testing::MaxNearestDistance(decoded->positions, mesh.positions);
    EXPECT_LT(error, last_error) << bpv;
    last_error = error;
  }
  EXPECT_LT(last_error, 5e-3 * diagonal);
}

TEST_P(ZerotreeCodec, EncodingIsDeterministic) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithKept(3);
  auto a = Encode(mesh, ZerotreeOptions(GetParam(), 6.0));
  auto b = Encode(mesh, ZerotreeOptions(GetParam(), 6.0));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, *b);
}

INSTANTIATE_TEST_SUITE_P(Kinds, ZerotreeCodec, ::testing::Values(TransformId::kUnlifted, TransformId::kLifted));

TEST(ZerotreeCodec, LambdaPicksTheLastBitPlane) {
  EXPECT_EQ(ZerotreePlaneForLambda(ZerotreeLambdaForPlane(7)), 7);
  EXPECT_EQ(ZerotreePlaneForLambda(1e9), 0);
  EXPECT_EQ(ZerotreePlaneForLambda(1e-40), 40);
  const SemiRegularMesh mesh = testing::MakeBumpySphere(3);
  size_t last_size = 0;
  for (const int plane : {9, 6, 3}) {
    EncodeOptions options;
    options.coder = CoderId::kZerotree;
    options.lambda = ZerotreeLambdaForPlane(plane);
    auto bytes = Encode(mesh, options);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    EXPECT_GT(bytes->size(), last_size) << plane;
    last_size = bytes->size();
  }
}

// Every prefix: the strict decoder rejects it; the truncated decoder either
// refuses it (before the base ends) or decodes every level, from the part of the
// embedded payload it has, with a finite result.
TEST(ZerotreeCodec, EveryPrefixIsRejectedOrDecodesAllLevels) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithKept(2);
  auto stream = Encode(mesh, ZerotreeOptions(TransformId::kUnlifted, 6.0));
  ASSERT_TRUE(stream.ok());
  auto info = ReadStreamInfo(stream->data(), stream->size());
  ASSERT_TRUE(info.ok());
  ASSERT_EQ(info->coder, CoderId::kZerotree);
  const size_t payload = info->level_offsets[0];
  // The payload header: 6 fixed bytes and the symbol count's varint.
  size_t header_end = payload + 6;
  while ((*stream)[header_end] & 0x80) ++header_end;
  for (size_t n = 0; n < stream->size(); ++n) {
    EXPECT_FALSE(Decode(stream->data(), n).ok()) << n;
    DecodeOptions partial;
    partial.allow_truncated = true;
    DecodeInfo decode_info;
    auto decoded = Decode(stream->data(), n, partial, &decode_info);
    if (n < info->prefix_size[0]) {
      EXPECT_FALSE(decoded.ok()) << n;
      continue;
    }
    ASSERT_TRUE(decoded.ok()) << n << ": " << decoded.status().ToString();
    EXPECT_EQ(decode_info.levels_decoded, n > header_end ? 2 : 0) << n;
    for (const Vec3& p : decoded->positions) ASSERT_TRUE(p.allFinite()) << n;
  }
}

TEST(ZerotreeCodec, LongerPrefixesDecodeCloser) {
  const SemiRegularMesh mesh = testing::MakeBumpySphere(3);
  auto stream = Encode(mesh, ZerotreeOptions(TransformId::kUnlifted, 24.0));
  ASSERT_TRUE(stream.ok());
  auto info = ReadStreamInfo(stream->data(), stream->size());
  ASSERT_TRUE(info.ok());
  DecodeOptions partial;
  partial.allow_truncated = true;
  double last_error = 1e300;
  const size_t start = info->level_offsets[0] + 16;
  for (size_t n = start; n <= stream->size(); n += (stream->size() - start) / 3) {
    auto decoded = Decode(stream->data(), n, partial);
    ASSERT_TRUE(decoded.ok()) << n;
    const double error = testing::MaxNearestDistance(decoded->positions, mesh.positions);
    EXPECT_LT(error, last_error) << n;
    last_error = error;
  }
}

// --level K: the embedded payload holds every level's coefficients; level K is
// synthesised from them (the coarser levels of the same decode).
TEST(ZerotreeCodec, LevelOptionGivesTheCoarserLevelsOfTheFullDecode) {
  const SemiRegularMesh mesh = testing::MakeBumpySphereWithKept(3);
  auto bytes = Encode(mesh, ZerotreeOptions(TransformId::kLifted, 8.0));
  ASSERT_TRUE(bytes.ok());
  testing::ExpectEachMaxLevelGivesItsCounts(*bytes, mesh);
}

TEST(ZerotreeCodec, PsnrTargetIsMetByTheSearchedBudget) {
  const SemiRegularMesh mesh = testing::MakeBumpySphere(2);
  const Mesh original = ExtractLevel(mesh, 2);
  EncodeOptions options;
  options.coder = CoderId::kZerotree;
  options.original = &original;
  options.target_psnr = 60.0;
  // 100k samples per measurement, not the meter's default 1M: the same property at
  // a tenth of the cost (40 s under the sanitizers at the default).
  options.psnr_samples = 100'000;
  EncodeReport report;
  auto bytes = Encode(mesh, options, &report);
  ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
  ASSERT_TRUE(report.psnr_measured);
  EXPECT_GE(report.psnr_db, 60.0);
  auto decoded = Decode(bytes->data(), bytes->size());
  ASSERT_TRUE(decoded.ok());
  CompareOptions compare;
  compare.samples = options.psnr_samples;
  auto distance = CompareSurfaces(original, *decoded, compare);
  ASSERT_TRUE(distance.ok());
  EXPECT_DOUBLE_EQ(distance->psnr_db, report.psnr_db);
}

}  // namespace
}  // namespace eqmesh

// The decoder on truncated, corrupted and random input: an error or a bounded
// mesh, never a crash (these tests also run under ASan/UBSan).
#include <gtest/gtest.h>

#include <random>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/encoder.h"

namespace eqmesh {
namespace {

std::vector<uint8_t> SmallStream() {
  EncodeOptions options;
  options.lambda = 0.05;
  return Encode(testing::MakeBumpySphereWithKept(2), options).value();
}

void ExpectBounded(const StatusOr<Mesh>& mesh) {
  if (!mesh.ok()) return;
  EXPECT_LE(mesh->positions.size(), 1u << 22);
  for (const Vec3& p : mesh->positions) EXPECT_TRUE(p.allFinite());
}

TEST(DecodeSafety, EveryPrefixIsRejectedOrDecodesItsCompleteLevels) {
  const std::vector<uint8_t> stream = SmallStream();
  auto info = ReadStreamInfo(stream.data(), stream.size());
  ASSERT_TRUE(info.ok());
  ASSERT_EQ(info->total_size, stream.size());
  for (size_t n = 0; n < stream.size(); ++n) {
    EXPECT_FALSE(Decode(stream.data(), n).ok()) << n;
    DecodeOptions partial;
    partial.allow_truncated = true;
    DecodeInfo decode_info;
    auto mesh = Decode(stream.data(), n, partial, &decode_info);
    if (n < info->prefix_size[0]) {
      EXPECT_FALSE(mesh.ok()) << n;
      continue;
    }
    ASSERT_TRUE(mesh.ok()) << n << ": " << mesh.status().ToString();
    int expected = 0;
    while (expected < info->levels && info->prefix_size[expected + 1] <= n) ++expected;
    EXPECT_EQ(decode_info.levels_decoded, expected) << n;
    EXPECT_TRUE(decode_info.truncated);
  }
  EXPECT_TRUE(Decode(stream.data(), stream.size()).ok());
}

TEST(DecodeSafety, TrailingBytesAreRejected) {
  std::vector<uint8_t> stream = SmallStream();
  stream.push_back(0);
  EXPECT_EQ(Decode(stream.data(), stream.size()).status().code(), StatusCode::kCorruptStream);
}

TEST(DecodeSafety, FlippedBytesNeverCrash) {
  const std::vector<uint8_t> stream = SmallStream();
  std::mt19937 rng(7);
  for (size_t i = 0; i < stream.size(); ++i) {
    std::vector<uint8_t> bad = stream;
    bad[i] ^= static_cast<uint8_t>(1u << (rng() % 8));
    ExpectBounded(Decode(bad.data(), bad.size()));
    bad[i] = static_cast<uint8_t>(rng());
    DecodeOptions partial;
    partial.allow_truncated = true;
    ExpectBounded(Decode(bad.data(), bad.size(), partial));
  }
}

TEST(DecodeSafety, RandomGarbageIsRejected) {
  std::mt19937 rng(11);
  const std::vector<uint8_t> stream = SmallStream();
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> garbage(rng() % 400);
    for (uint8_t& b : garbage) b = static_cast<uint8_t>(rng());
    EXPECT_FALSE(Decode(garbage.data(), garbage.size()).ok());
    // Valid header, garbage chunks.
    auto info = ReadStreamInfo(stream.data(), stream.size()).value();
    std::vector<uint8_t> mixed(stream.begin(), stream.begin() + info.header_size);
    for (uint64_t i = info.header_size; i < stream.size(); ++i) mixed.push_back(static_cast<uint8_t>(rng()));
    ExpectBounded(Decode(mixed.data(), mixed.size()));
  }
}

TEST(DecodeSafety, HostileCountsAreRefusedBeforeAllocating) {
  std::vector<uint8_t> stream = SmallStream();
  auto info = ReadStreamInfo(stream.data(), stream.size()).value();
  // Claim a 4 GiB base chunk: must fail on the length check, not allocate.
  std::vector<uint8_t> bad(stream.begin(), stream.begin() + 14);
  for (int i = 0; i < 4; ++i) bad.push_back(0xFF);
  bad.push_back(0x0F);
  EXPECT_FALSE(Decode(bad.data(), bad.size()).ok());
  EXPECT_GT(info.levels, 0);
}

}  // namespace
}  // namespace eqmesh

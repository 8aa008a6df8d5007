// The decoder on truncated, corrupted and random input: an error or a bounded
// mesh, never a crash (these tests also run under ASan/UBSan). In the spirit of
// meshoptimizer's decoder tests: every prefix of every sample stream, trailing
// bytes, bad magic vs unknown version, headers that lie about their sizes. How much
// the decoder allocates for such headers is measured by
// tests/fuzz_regressions/decode_alloc_bound_test.cpp.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "coding/entropy/byte_io.h"
#include "coding/stream_header.h"

namespace eqmesh {
namespace {

using bitstream::CoderId;
using bitstream::TransformId;

std::vector<uint8_t> SmallStream() {
  EncodeOptions options;
  options.lambda = 0.05;
  return Encode(testing::MakeBumpySphereWithKept(2), options).value();
}

struct Sample {
  std::string name;
  std::vector<uint8_t> bytes;
};

std::vector<uint8_t> EncodeSample(CoderId coder, TransformId transform, bool kept, bool draco_base = false,
                                  bool creases = false) {
  EncodeOptions options;
  options.draco_base = draco_base;
  options.lambda = 0.05;
  options.coder = coder;
  options.transform = transform;
  const SemiRegularMesh mesh = creases ? testing::MakeBumpySphereWithCreases(2)
                               : kept  ? testing::MakeBumpySphereWithKept(2)
                                       : testing::MakeBumpySphere(2);
  auto bytes = Encode(mesh, options);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::vector<uint8_t>();
}

// Both coders (and the uniform baseline), both transforms, kept-exactly components,
// and the golden streams as committed.
const std::vector<Sample>& Samples() {
  static const std::vector<Sample> samples = [] {
    std::vector<Sample> s;
    s.push_back({"eq_unlifted_kept", EncodeSample(CoderId::kEq, TransformId::kUnlifted, true)});
    s.push_back({"eq_lifted", EncodeSample(CoderId::kEq, TransformId::kLifted, false)});
    s.push_back({"zerotree_unlifted", EncodeSample(CoderId::kZerotree, TransformId::kUnlifted, false)});
    s.push_back({"zerotree_lifted_kept", EncodeSample(CoderId::kZerotree, TransformId::kLifted, true)});
    s.push_back({"uniform_lifted_kept", EncodeSample(CoderId::kUniform, TransformId::kLifted, true)});
    s.push_back({"eq_draco_base_kept", EncodeSample(CoderId::kEq, TransformId::kUnlifted, true, true)});
    s.push_back({"eq_lifted_creases", EncodeSample(CoderId::kEq, TransformId::kLifted, false, false, true)});
    s.push_back({"zerotree_unlifted_creases", EncodeSample(CoderId::kZerotree, TransformId::kUnlifted, false, false, true)});
    const std::string data = std::string(EQMESH_SOURCE_DIR) + "/tests/codec/data/";
    s.push_back({"golden_v1_3", testing::ReadBytes(data + "golden_v1_3.eqm")});
    s.push_back({"golden_v1_2", testing::ReadBytes(data + "golden_v1_2.eqm")});
    s.push_back({"golden_v1_1", testing::ReadBytes(data + "golden_v1_1.eqm")});
    s.push_back({"golden_v1_0", testing::ReadBytes(data + "golden_v1_0.eqm")});
    s.push_back({"golden_v1_1_single_lambda", testing::ReadBytes(data + "golden_v1_1_single_lambda.eqm")});
    s.push_back({"golden_v1_1_full_base_weight", testing::ReadBytes(data + "golden_v1_1_full_base_weight.eqm")});
    return s;
  }();
  return samples;
}

void ExpectBounded(const StatusOr<Mesh>& mesh) {
  if (!mesh.ok()) return;
  EXPECT_LE(mesh->positions.size(), 1u << 22);
  for (const Vec3& p : mesh->positions) EXPECT_TRUE(p.allFinite());
}

// Bytes of the zerotree payload header (6 fixed bytes + the symbol count varint,
// zerotree_coder.h), read independently of the decoder.
uint64_t ZerotreeHeaderBytes(const std::vector<uint8_t>& stream, const StreamInfo& info) {
  ByteReader r(stream.data() + info.level_offsets[0] + 6, info.level_sizes[0] - 6, "test");
  uint64_t symbols = 0;
  EXPECT_TRUE(r.ReadVarint(&symbols).ok());
  return 6 + r.offset();
}

// Levels a prefix of n bytes must give: EQ and uniform the complete level chunks,
// zerotree every level once its payload header is in.
int ExpectedLevels(const std::vector<uint8_t>& stream, const StreamInfo& info, size_t n) {
  if (info.coder == CoderId::kZerotree) {
    if (info.levels == 0) return 0;
    return n >= info.level_offsets[0] + ZerotreeHeaderBytes(stream, info) ? info.levels : 0;
  }
  int levels = 0;
  while (levels < info.levels && info.prefix_size[static_cast<size_t>(levels) + 1] <= n) ++levels;
  return levels;
}

TEST(DecodeSafety, EveryPrefixOfEverySampleIsRejectedOrDecodesItsCompleteLevels) {
  for (const Sample& sample : Samples()) {
    SCOPED_TRACE(sample.name);
    const std::vector<uint8_t>& stream = sample.bytes;
    ASSERT_FALSE(stream.empty());
    auto info = ReadStreamInfo(stream.data(), stream.size());
    ASSERT_TRUE(info.ok()) << info.status().ToString();
    ASSERT_EQ(info->total_size, stream.size());
    ASSERT_GT(info->levels, 0);
    // The complete levels each prefix may give, decoded from the whole stream.
    std::vector<Mesh> by_level;
    for (int k = 0; k <= info->levels; ++k) {
      DecodeOptions options;
      options.max_level = k;
      by_level.push_back(Decode(stream.data(), stream.size(), options).value());
    }
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
      const int expected = ExpectedLevels(stream, *info, n);
      ASSERT_EQ(decode_info.levels_decoded, expected) << n;
      EXPECT_TRUE(decode_info.truncated);
      const Mesh& whole = by_level[static_cast<size_t>(expected)];
      ASSERT_EQ(mesh->positions.size(), whole.positions.size()) << n;
      EXPECT_EQ(mesh->faces, whole.faces) << n;
      // EQ / uniform levels do not depend on later chunks: the same positions. A
      // zerotree prefix gives every level at a coarser quality, finite.
      if (info->coder != CoderId::kZerotree) {
        EXPECT_EQ(mesh->positions, whole.positions) << n;
      } else {
        for (const Vec3& p : mesh->positions) ASSERT_TRUE(p.allFinite()) << n;
      }
    }
    EXPECT_TRUE(Decode(stream.data(), stream.size()).ok());
  }
}

TEST(DecodeSafety, TrailingBytesAreRejected) {
  for (const Sample& sample : Samples()) {
    SCOPED_TRACE(sample.name);
    for (const size_t extra : {size_t{1}, size_t{7}, size_t{1000}}) {
      std::vector<uint8_t> stream = sample.bytes;
      stream.resize(stream.size() + extra, 0);
      for (const bool allow_truncated : {false, true}) {
        DecodeOptions options;
        options.allow_truncated = allow_truncated;
        auto mesh = Decode(stream.data(), stream.size(), options);
        ASSERT_FALSE(mesh.ok());
        EXPECT_EQ(mesh.status().code(), StatusCode::kCorruptStream);
        EXPECT_NE(mesh.status().message().find("trailing"), std::string::npos) << mesh.status().message();
      }
    }
  }
}

TEST(DecodeSafety, BadMagicAndUnknownVersionGiveDistinctErrors) {
  const std::vector<uint8_t> good = SmallStream();
  std::vector<uint8_t> bad_magic = good;
  bad_magic[0] = 'X';
  std::vector<uint8_t> new_major = good;
  new_major[4] = bitstream::kVersionMajor + 1;
  const Status magic = Decode(bad_magic.data(), bad_magic.size()).status();
  const Status version = Decode(new_major.data(), new_major.size()).status();
  EXPECT_EQ(magic.code(), StatusCode::kCorruptStream);
  EXPECT_EQ(version.code(), StatusCode::kUnsupportedVersion);
  EXPECT_NE(magic.message(), version.message());
  EXPECT_NE(magic.message().find("bad magic"), std::string::npos) << magic.message();
  const std::string expected = "version 2." + std::to_string(good[5]);
  EXPECT_NE(version.message().find(expected), std::string::npos) << version.message();
  // The header parser alone says the same.
  EXPECT_EQ(ReadStreamInfo(bad_magic.data(), bad_magic.size()).status().code(), StatusCode::kCorruptStream);
  EXPECT_EQ(ReadStreamInfo(new_major.data(), new_major.size()).status().code(), StatusCode::kUnsupportedVersion);
  // A version byte alone is enough to tell: a stream cut right after it.
  EXPECT_EQ(Decode(new_major.data(), 6).status().code(), StatusCode::kUnsupportedVersion);
  EXPECT_EQ(Decode(bad_magic.data(), 4).status().code(), StatusCode::kCorruptStream);
}

TEST(DecodeSafety, NewerMinorVersionDecodesUnlessItUsesSomethingNew) {
  std::vector<uint8_t> stream = SmallStream();
  stream[5] = 200;  // a future minor version with no new flag or id: readable
  EXPECT_TRUE(Decode(stream.data(), stream.size()).ok());
  std::vector<uint8_t> new_coder = stream;
  new_coder[7] = bitstream::kMaxCoderId + 1;
  EXPECT_EQ(Decode(new_coder.data(), new_coder.size()).status().code(), StatusCode::kUnsupportedFeature);
  std::vector<uint8_t> new_transform = stream;
  new_transform[6] = 2;
  EXPECT_EQ(Decode(new_transform.data(), new_transform.size()).status().code(), StatusCode::kUnsupportedFeature);
  std::vector<uint8_t> new_flag = stream;
  new_flag[9] |= 0x80;
  EXPECT_EQ(Decode(new_flag.data(), new_flag.size()).status().code(), StatusCode::kCorruptStream);
}

// Flag bit 2 (1.3) describes EQ level chunks; on another coder it is corrupt.
TEST(DecodeSafety, TangentialContextFlagOnlyOnEqStreams) {
  for (const Sample& sample : Samples()) {
    if (sample.bytes.size() < 10) continue;
    auto info = ReadStreamInfo(sample.bytes.data(), sample.bytes.size());
    ASSERT_TRUE(info.ok()) << sample.name;
    std::vector<uint8_t> flagged = sample.bytes;
    flagged[9] |= bitstream::kTangentialContext;
    const auto decoded = Decode(flagged.data(), flagged.size());
    if (info->coder == CoderId::kEq) {
      ExpectBounded(decoded);  // 1.2 chunks read as 1.3 ones: garbage or an error, bounded
    } else {
      EXPECT_EQ(decoded.status().code(), StatusCode::kCorruptStream) << sample.name;
    }
  }
}

TEST(DecodeSafety, FlippedBytesNeverCrash) {
  for (const Sample& sample : Samples()) {
    SCOPED_TRACE(sample.name);
    const std::vector<uint8_t>& stream = sample.bytes;
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
    std::vector<uint8_t> mixed(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(info.header_size));
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

// The header rewritten to claim `levels` levels, the extra level chunks `extra`
// bytes of filler each (the real chunks kept).
std::vector<uint8_t> WithMoreLevels(const std::vector<uint8_t>& stream, int levels, uint64_t extra, uint8_t fill) {
  size_t header_size = 0;
  StreamHeader h = ReadStreamHeader(stream.data(), stream.size(), &header_size).value();
  const size_t old_levels = h.level_sizes.size();
  h.levels = levels;
  h.level_sizes.resize(static_cast<size_t>(levels), extra);
  std::vector<uint8_t> out = WriteStreamHeader(h);
  out.insert(out.end(), stream.begin() + static_cast<std::ptrdiff_t>(header_size), stream.end());
  out.resize(out.size() + (static_cast<size_t>(levels) - old_levels) * extra, fill);
  return out;
}

// The stream with one `fill` byte appended to chunk `chunk` (-1: the base chunk,
// j >= 0: level chunk j) and the header rewritten to claim it.
// WithPaddedChunk's names for the chunks before the levels (levels are 0, 1, ...).
constexpr int kBaseChunk = -1;
constexpr int kCreaseChunk = -2;

std::vector<uint8_t> WithPaddedChunk(const std::vector<uint8_t>& stream, int chunk, uint8_t fill) {
  const StreamInfo info = ReadStreamInfo(stream.data(), stream.size()).value();
  size_t header_size = 0;
  StreamHeader h = ReadStreamHeader(stream.data(), stream.size(), &header_size).value();
  uint64_t end = info.base_offset + info.base_size;
  if (chunk == kBaseChunk) {
    ++h.base_size;
  } else if (chunk == kCreaseChunk) {
    end = info.crease_offset + info.crease_size;
    ++h.crease_size;
  } else {
    const size_t j = static_cast<size_t>(chunk);
    end = info.level_offsets[j] + info.level_sizes[j];
    ++h.level_sizes[j];
  }
  std::vector<uint8_t> out = WriteStreamHeader(h);
  out.insert(out.end(), stream.begin() + static_cast<std::ptrdiff_t>(header_size),
             stream.begin() + static_cast<std::ptrdiff_t>(end));
  out.push_back(fill);
  out.insert(out.end(), stream.begin() + static_cast<std::ptrdiff_t>(end), stream.end());
  return out;
}

// Every range-coded chunk is consumed exactly (ext_spec A.4.1), so a byte the
// header counts but no symbol reads is refused (the spec's "level chunk with bytes
// left over"). Not for the zerotree coder, whose embedded chunk may end anywhere,
// nor for Draco base chunks.
TEST(DecodeSafety, ChunksWithBytesLeftOverAreRejected) {
  for (const Sample& sample : Samples()) {
    if (sample.name.rfind("zerotree", 0) == 0) continue;
    SCOPED_TRACE(sample.name);
    const StreamInfo info = ReadStreamInfo(sample.bytes.data(), sample.bytes.size()).value();
    ASSERT_TRUE(Decode(sample.bytes.data(), sample.bytes.size()).ok());
    std::vector<int> chunks;
    if (info.has_creases) chunks.push_back(kCreaseChunk);
    if (info.has_compact_base) chunks.push_back(kBaseChunk);
    for (int j = 0; j < info.levels; ++j) chunks.push_back(j);
    for (const int chunk : chunks) {
      for (const uint8_t fill : {uint8_t{0}, uint8_t{0xA5}}) {
        const std::vector<uint8_t> bad = WithPaddedChunk(sample.bytes, chunk, fill);
        auto mesh = Decode(bad.data(), bad.size());
        ASSERT_FALSE(mesh.ok()) << "chunk " << chunk << " fill " << int{fill};
        EXPECT_EQ(mesh.status().code(), StatusCode::kCorruptStream) << mesh.status().ToString();
      }
    }
  }
}

// More levels than the data holds: refused (corrupt or over the format limits),
// level by level, whatever the filler.
TEST(DecodeSafety, HeaderClaimingMoreLevelsIsRejected) {
  for (const Sample& sample : Samples()) {
    SCOPED_TRACE(sample.name);
    for (int levels = 3; levels <= bitstream::kMaxLevels; ++levels) {
      for (const uint64_t extra : {uint64_t{0}, uint64_t{1}, uint64_t{9}, uint64_t{64}}) {
        for (const uint8_t fill : {uint8_t{0}, uint8_t{0xFF}}) {
          const std::vector<uint8_t> bad = WithMoreLevels(sample.bytes, levels, extra, fill);
          auto mesh = Decode(bad.data(), bad.size());
          // The uniform coder has no count field: zero filler may be a valid chunk
          // of zero coefficients (as many as its bytes can hold).
          if (mesh.ok() && sample.name.rfind("uniform", 0) == 0) {
            ExpectBounded(mesh);
            continue;
          }
          ASSERT_FALSE(mesh.ok()) << levels << " levels, " << extra << " bytes each";
          const StatusCode code = mesh.status().code();
          EXPECT_TRUE(code == StatusCode::kCorruptStream || code == StatusCode::kResourceLimit)
              << mesh.status().ToString();
        }
      }
    }
  }
}

// A level count no stream may have, and a base that refined that often exceeds the
// face limit: ResourceLimit, from the header and base alone.
TEST(DecodeSafety, LevelsBeyondTheFaceLimitAreAResourceLimit) {
  const std::vector<uint8_t> stream = SmallStream();
  std::vector<uint8_t> over = stream;
  over[8] = bitstream::kMaxLevels + 1;
  EXPECT_EQ(Decode(over.data(), over.size()).status().code(), StatusCode::kCorruptStream);
  // 20 base faces * 4^11 > 2^24.
  const std::vector<uint8_t> deep = WithMoreLevels(stream, 11, 16, 0);
  EXPECT_EQ(Decode(deep.data(), deep.size()).status().code(), StatusCode::kResourceLimit);
}

}  // namespace
}  // namespace eqmesh

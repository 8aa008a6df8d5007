// The compact base-mesh chunk (lib/coding/compact_base/): exact round trips of
// connectivity and quantized positions on closed, open, multi-component and
// higher-genus meshes; refusal of what it does not code; decode safety on every
// prefix, corrupted bytes and hostile counts.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <string>

#include "codec/compact_chunk_checks.h"
#include "coding/compact_base/compact_base_decoder.h"
#include "coding/compact_base/compact_base_encoder.h"
#include "coding/compact_base/compact_base_model.h"
#include "coding/entropy/byte_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

using FaceSet = std::set<std::array<uint32_t, 3>>;

// Faces as cyclic triples starting at their smallest corner (orientation kept).
FaceSet Canonical(const std::vector<Face>& faces, const std::vector<uint32_t>* map = nullptr) {
  FaceSet out;
  for (const Face& f : faces) {
    std::array<uint32_t, 3> t{f[0], f[1], f[2]};
    if (map) t = {(*map)[t[0]], (*map)[t[1]], (*map)[t[2]]};
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    out.insert(t);
  }
  return out;
}

Mesh TwoComponents() {
  return testing::WithComponent(testing::MakeIcosphere(1), testing::MakeTorus(8, 6), Vec3(3.0, 0.0, 0.0));
}

void ExpectRoundTrip(const Mesh& mesh, int bits, const std::string& name) {
  SCOPED_TRACE(name + " at " + std::to_string(bits) + " bits");
  auto enc = EncodeCompactBase(mesh, bits);
  ASSERT_TRUE(enc.ok()) << enc.status().ToString();
  auto dec = DecodeCompactBase(enc->bytes.data(), enc->bytes.size(), 1u << 20, "test");
  ASSERT_TRUE(dec.ok()) << dec.status().ToString();
  ASSERT_EQ(dec->positions.size(), mesh.positions.size());
  EXPECT_EQ(dec->faces, enc->decoded.faces);
  EXPECT_EQ(dec->positions, enc->decoded.positions);  // bit for bit what the encoder assumed
  EXPECT_EQ(Canonical(dec->faces, &enc->decoded_to_input), Canonical(mesh.faces));
  const double step = testing::LargestExtent(mesh) / (std::ldexp(1.0, bits) - 1.0);
  for (size_t i = 0; i < dec->positions.size(); ++i) {
    const Vec3 d = dec->positions[i] - mesh.positions[enc->decoded_to_input[i]];
    EXPECT_LE(d.cwiseAbs().maxCoeff(), 0.5 * step * (1 + 1e-6) + 1e-7 * testing::LargestExtent(mesh)) << "vertex " << i;
  }
}

TEST(CompactBase, RoundTripsClosedOpenMultiComponentAndGenusOneMeshes) {
  const std::pair<const char*, Mesh> meshes[] = {
      {"icosphere", testing::MakeIcosphere(2)},
      {"disc", testing::MakeDisc(4)},
      {"torus", testing::MakeTorus(12, 8)},
      {"two components", TwoComponents()}};
  for (const auto& [name, mesh] : meshes) {
    for (const int bits : {1, 8, 12, 20, kCompactMaxBits}) ExpectRoundTrip(mesh, bits, name);
  }
}

TEST(CompactBase, IsSmallerThanRawOnASmoothBase) {
  const Mesh mesh = testing::MakeIcosphere(3);  // 642 vertices
  auto enc = EncodeCompactBase(mesh, 12);
  ASSERT_TRUE(enc.ok());
  const size_t raw_positions = mesh.positions.size() * 3 * 12 / 8;
  EXPECT_LT(enc->bytes.size(), raw_positions);
}

TEST(CompactBase, RefusesWhatItDoesNotCode) {
  Mesh flipped = testing::MakeIcosphere(1);
  std::swap(flipped.faces[3][0], flipped.faces[3][1]);
  EXPECT_EQ(EncodeCompactBase(flipped, 10).status().code(), StatusCode::kUnsupportedFeature);
  Mesh fin = testing::MakeIcosphere(1);  // a third face on edge (f0[0], f0[1])
  fin.positions.push_back(Vec3(2, 2, 2));
  fin.faces.push_back({fin.faces[0][0], fin.faces[0][1], static_cast<uint32_t>(fin.positions.size() - 1)});
  EXPECT_EQ(EncodeCompactBase(fin, 10).status().code(), StatusCode::kUnsupportedFeature);
  Mesh loose = testing::MakeIcosphere(1);
  loose.positions.push_back(Vec3(5, 5, 5));  // on no face
  EXPECT_EQ(EncodeCompactBase(loose, 10).status().code(), StatusCode::kUnsupportedFeature);
  EXPECT_FALSE(EncodeCompactBase(loose, 0).ok());
  EXPECT_FALSE(EncodeCompactBase(loose, kCompactMaxBits + 1).ok());
}

TEST(CompactBase, EveryPrefixAndCorruptedByteIsAnErrorOrAValidMesh) {
  auto enc = EncodeCompactBase(TwoComponents(), 10);
  ASSERT_TRUE(enc.ok());
  const std::vector<uint8_t>& good = enc->bytes;
  for (size_t n = 0; n < good.size(); ++n) {
    const std::vector<uint8_t> prefix(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    testing::ExpectErrorOrValidCompactMesh(prefix, 1u << 20);
  }
  uint32_t state = 12345;
  for (size_t at = 0; at < good.size(); ++at) {
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<uint8_t> bad = good;
      state = state * 1664525u + 1013904223u;
      bad[at] = static_cast<uint8_t>(bad[at] ^ (1u + (state >> 24) % 255u));
      testing::ExpectErrorOrValidCompactMesh(bad, 1u << 20);
    }
  }
}

TEST(CompactBase, BytesLeftOverAreRejected) {
  auto enc = EncodeCompactBase(TwoComponents(), 10);
  ASSERT_TRUE(enc.ok());
  std::vector<uint8_t> padded = enc->bytes;
  padded.push_back(0);
  auto dec = DecodeCompactBase(padded.data(), padded.size(), 1u << 20, "test");
  ASSERT_FALSE(dec.ok());
  EXPECT_EQ(dec.status().code(), StatusCode::kCorruptStream);
}

std::vector<uint8_t> ChunkClaiming(uint64_t vertices, uint64_t faces, size_t payload_bytes) {
  ByteWriter w;
  w.PutVarint(vertices);
  w.PutVarint(faces);
  w.PutU8(10);
  for (int k = 0; k < 3; ++k) w.PutF32(0.0f);
  w.PutF32(1.0f);
  for (size_t i = 0; i < payload_bytes; ++i) w.PutU8(0xFF);
  return w.Take();
}

TEST(CompactBase, HostileCountsAreRefusedBeforeAllocation) {
  // More vertices than the caller allows, than the payload can hold, or faces
  // beyond the per-vertex rule: each refused from the chunk head alone.
  auto over_limit = DecodeCompactBase(ChunkClaiming(1u << 20, 100, 64).data(), 64 + 20, 1000, "test");
  EXPECT_EQ(over_limit.status().code(), StatusCode::kCorruptStream);
  const std::vector<uint8_t> thin = ChunkClaiming(1u << 19, 1u << 20, 16);
  EXPECT_EQ(DecodeCompactBase(thin.data(), thin.size(), 1u << 20, "test").status().code(),
            StatusCode::kResourceLimit);
  const std::vector<uint8_t> faces = ChunkClaiming(100, 100 * kCompactMaxFacesPerVertex + kCompactFaceSlack + 1, 64);
  EXPECT_EQ(DecodeCompactBase(faces.data(), faces.size(), 1u << 20, "test").status().code(),
            StatusCode::kCorruptStream);
  // Counts within the rules but payload noise: an error, never a hang.
  const std::vector<uint8_t> noise = ChunkClaiming(1000, 2000, 64);
  testing::ExpectErrorOrValidCompactMesh(noise, 1u << 20);
}

}  // namespace
}  // namespace eqmesh

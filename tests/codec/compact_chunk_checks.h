// Decode-safety check shared by the compact chunk's tests.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/compact_base/compact_base_decoder.h"

namespace eqmesh::testing {

// A damaged or truncated chunk decodes to a corrupt-stream or resource-limit error,
// or to a mesh whose indices are in range and whose positions are finite.
inline void ExpectErrorOrValidCompactMesh(const std::vector<uint8_t>& bytes, uint32_t max_vertices) {
  auto dec = DecodeCompactBase(bytes.data(), bytes.size(), max_vertices, "test");
  if (!dec.ok()) {
    EXPECT_TRUE(dec.status().code() == StatusCode::kCorruptStream ||
                dec.status().code() == StatusCode::kResourceLimit)
        << dec.status().ToString();
    return;
  }
  for (const Face& f : dec->faces) {
    for (const uint32_t v : f) EXPECT_LT(v, dec->positions.size());
  }
  for (const Vec3& p : dec->positions) EXPECT_TRUE(p.allFinite());
}

// Every prefix of `good` (in steps of 3 bytes) and every one-byte corruption of it
// (a pseudo-random xor per position, from `seed`) decodes safely.
inline void ExpectDamagedCompactChunksSafe(const std::vector<uint8_t>& good, uint32_t seed) {
  for (size_t n = 0; n < good.size(); n += 3) {
    ExpectErrorOrValidCompactMesh(std::vector<uint8_t>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n)),
                                  1u << 20);
  }
  uint32_t state = seed;
  for (size_t at = 0; at < good.size(); ++at) {
    std::vector<uint8_t> bad = good;
    state = state * 1664525u + 1013904223u;
    bad[at] = static_cast<uint8_t>(bad[at] ^ (1u + (state >> 24) % 255u));
    ExpectErrorOrValidCompactMesh(bad, 1u << 20);
  }
}

}  // namespace eqmesh::testing

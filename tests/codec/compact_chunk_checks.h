// Decode-safety check shared by the compact chunk's tests.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace eqmesh::testing

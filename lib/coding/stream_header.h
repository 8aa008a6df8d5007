// The .eqm stream header (layout in bitstream_shared.h): reading, writing, and the
// byte ranges of the chunks it announces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/bitstream_shared.h"
#include "core/status.h"

namespace eqmesh {

struct StreamHeader {
  uint8_t version_major = bitstream::kVersionMajor;
  uint8_t version_minor = bitstream::kVersionMinorWithoutAtlas;
  bitstream::TransformId transform = bitstream::TransformId::kUnlifted;
  bitstream::CoderId coder = bitstream::CoderId::kEq;
  int levels = 0;
  uint8_t flags = 0;
  int64_t lambda_code = 0;
  int64_t tangential_code = 0;
  float quantum = 1.0f;
  uint64_t base_size = 0;
  uint64_t kept_size = 0;  // 0 unless flags has kHasKeptExactly
  uint64_t atlas_size = 0; // 0 unless flags has kHasAtlas
  uint64_t crease_size = 0;  // 0 unless flags has kCreaseEdges
  std::vector<uint64_t> level_sizes;

  bool has_kept() const { return (flags & bitstream::kHasKeptExactly) != 0; }
  bool has_compact_base() const { return (flags & bitstream::kCompactBase) != 0; }
  bool has_tangential_context() const { return (flags & bitstream::kTangentialContext) != 0; }
  bool has_atlas() const { return (flags & bitstream::kHasAtlas) != 0; }
  bool has_compact_kept() const { return (flags & bitstream::kCompactKept) != 0; }
  bool has_positions_after() const { return (flags & bitstream::kCompactPositionsAfter) != 0; }
  bool has_creases() const { return (flags & bitstream::kCreaseEdges) != 0; }
  double lambda() const;
  double tangential_factor() const;
};

// The code whose decoded value is closest to `value` (> 0) in the log domain.
int64_t LogCode(double value);
double FromLogCode(int64_t code);

std::vector<uint8_t> WriteStreamHeader(const StreamHeader& header);

// Parses and validates the header; *header_size receives its byte length. The
// chunks themselves need not be present (truncation is the caller's decision).
// Bad magic -> kCorruptStream ("not an eqmesh stream (bad magic)"); unknown major
// version -> kUnsupportedVersion; unknown transform or coder id -> kUnsupportedFeature;
// anything else malformed -> kCorruptStream.
StatusOr<StreamHeader> ReadStreamHeader(const uint8_t* data, size_t size, size_t* header_size);

}  // namespace eqmesh

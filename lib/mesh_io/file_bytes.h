// Whole-file reads with transparent, size-capped gzip inflation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace eqmesh {

// Default cap on the bytes a file may yield after inflation.
constexpr uint64_t kDefaultMaxFileBytes = uint64_t{4} << 30;

// True when `bytes` start with the gzip magic 1f 8b.
bool IsGzip(const uint8_t* bytes, size_t size);

// Inflates one or more concatenated gzip members. Fails (kResourceLimit) as soon as
// the output would exceed `max_bytes`, so a zip bomb costs at most max_bytes of
// memory; fails (kParseError) on corrupt or truncated data. `name` prefixes errors.
StatusOr<std::vector<uint8_t>> InflateGzip(const uint8_t* bytes, size_t size, uint64_t max_bytes,
                                           const std::string& name);

// Reads `path` whole; a gzip file (by magic, not by name) is inflated. Neither the
// file nor its inflated contents may exceed `max_bytes`. `was_gzip`, when given,
// tells whether inflation happened.
StatusOr<std::vector<uint8_t>> ReadFileBytes(const std::string& path,
                                             uint64_t max_bytes = kDefaultMaxFileBytes,
                                             bool* was_gzip = nullptr);

}  // namespace eqmesh

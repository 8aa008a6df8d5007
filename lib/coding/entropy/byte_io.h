// Byte-level reading and writing for the eqmesh container: little-endian fixed
// width fields and LEB128 varints (zig-zag for signed values).
//
// ByteReader is the only way the decoder touches stream bytes: every read checks
// the remaining length first and reports kCorruptStream with the byte offset, so a
// truncated or hostile stream yields an error, never an out-of-bounds read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace eqmesh {

class ByteWriter {
 public:
  void PutU8(uint8_t v) { bytes_.push_back(v); }
  void PutU32(uint32_t v);
  void PutF32(float v);
  void PutVarint(uint64_t v);
  void PutSignedVarint(int64_t v);
  void PutBytes(const uint8_t* data, size_t size);
  void PutBytes(const std::vector<uint8_t>& data) { PutBytes(data.data(), data.size()); }

  size_t size() const { return bytes_.size(); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t> Take() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
};

// Number of bytes PutVarint writes for v (1..10).
size_t VarintSize(uint64_t v);

class ByteReader {
 public:
  // `what` names the structure being read in error messages ("eqm header").
  ByteReader(const uint8_t* data, size_t size, std::string what)
      : data_(data), size_(size), what_(std::move(what)) {}

  Status ReadU8(uint8_t* v);
  Status ReadU32(uint32_t* v);
  // Rejects NaN and infinities: no stream field may carry them.
  Status ReadFiniteF32(float* v);
  // LEB128, at most 10 bytes; overlong encodings are corrupt.
  Status ReadVarint(uint64_t* v);
  Status ReadSignedVarint(int64_t* v);
  // Varint that must lie in [0, max]: the check that precedes every allocation.
  Status ReadBoundedVarint(uint64_t max, const char* field, uint64_t* v);
  // Points *out at the next `size` bytes (no copy) and skips them.
  Status ReadSpan(size_t size, const uint8_t** out);

  size_t offset() const { return offset_; }
  size_t remaining() const { return size_ - offset_; }
  // Error naming the structure and the current offset.
  Status Corrupt(const std::string& problem) const;

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
  std::string what_;
};

}  // namespace eqmesh

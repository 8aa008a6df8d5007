#include "coding/entropy/byte_io.h"

#include <cmath>
#include <cstring>

namespace eqmesh {

void ByteWriter::PutU32(uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void ByteWriter::PutF32(float v) {
  uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  PutU32(bits);
}

void ByteWriter::PutVarint(uint64_t v) {
  while (v >= 0x80) {
    bytes_.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  bytes_.push_back(static_cast<uint8_t>(v));
}

void ByteWriter::PutSignedVarint(int64_t v) {
  // Zig-zag so small magnitudes of either sign stay short.
  const uint64_t u = (static_cast<uint64_t>(v) << 1) ^ static_cast<uint64_t>(v >> 63);
  PutVarint(u);
}

void ByteWriter::PutBytes(const uint8_t* data, size_t size) {
  if (size > 0) bytes_.insert(bytes_.end(), data, data + size);
}

size_t VarintSize(uint64_t v) {
  size_t n = 1;
  while (v >= 0x80) {
    v >>= 7;
    ++n;
  }
  return n;
}

Status ByteReader::Corrupt(const std::string& problem) const {
  return CorruptStream(what_ + " at byte " + std::to_string(offset_) + ": " + problem);
}

Status ByteReader::ReadU8(uint8_t* v) {
  if (remaining() < 1) return Corrupt("unexpected end of data");
  *v = data_[offset_++];
  return Status::Ok();
}

Status ByteReader::ReadU32(uint32_t* v) {
  if (remaining() < 4) return Corrupt("unexpected end of data");
  uint32_t out = 0;
  for (int i = 0; i < 4; ++i) out |= static_cast<uint32_t>(data_[offset_ + i]) << (8 * i);
  offset_ += 4;
  *v = out;
  return Status::Ok();
}

Status ByteReader::ReadFiniteF32(float* v) {
  uint32_t bits = 0;
  EQMESH_RETURN_IF_ERROR(ReadU32(&bits));
  float f = 0.0f;
  std::memcpy(&f, &bits, sizeof f);
  if (!std::isfinite(f)) return Corrupt("non-finite float");
  *v = f;
  return Status::Ok();
}

Status ByteReader::ReadVarint(uint64_t* v) {
  uint64_t out = 0;
  for (int i = 0; i < 10; ++i) {
    uint8_t byte = 0;
    EQMESH_RETURN_IF_ERROR(ReadU8(&byte));
    // The tenth byte may only carry the top bit of a 64-bit value.
    if (i == 9 && byte > 1) return Corrupt("varint overflows 64 bits");
    out |= static_cast<uint64_t>(byte & 0x7F) << (7 * i);
    if ((byte & 0x80) == 0) {
      // One value, one encoding (spec A.1): a zero final group after the first
      // byte only pads, so a stream could not be compared or hashed by value.
      if (i > 0 && byte == 0) return Corrupt("overlong varint (a final byte of 0)");
      *v = out;
      return Status::Ok();
    }
  }
  return Corrupt("varint longer than 10 bytes");
}

Status ByteReader::ReadSignedVarint(int64_t* v) {
  uint64_t u = 0;
  EQMESH_RETURN_IF_ERROR(ReadVarint(&u));
  *v = static_cast<int64_t>(u >> 1) ^ -static_cast<int64_t>(u & 1);
  return Status::Ok();
}

Status ByteReader::ReadBoundedVarint(uint64_t max, const char* field, uint64_t* v) {
  const size_t start = offset_;
  EQMESH_RETURN_IF_ERROR(ReadVarint(v));
  if (*v > max) {
    offset_ = start;
    return Corrupt(std::string(field) + " " + std::to_string(*v) + " exceeds the limit " +
                   std::to_string(max));
  }
  return Status::Ok();
}

Status ByteReader::ReadSpan(size_t size, const uint8_t** out) {
  if (size > remaining()) {
    return Corrupt("needs " + std::to_string(size) + " bytes, only " +
                   std::to_string(remaining()) + " left");
  }
  *out = data_ + offset_;
  offset_ += size;
  return Status::Ok();
}

}  // namespace eqmesh

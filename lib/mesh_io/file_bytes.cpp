#include "mesh_io/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sys/stat.h>

#include <zlib.h>

namespace eqmesh {
namespace {

// zlib counts in 32-bit uInt, so large buffers are fed in slices.
constexpr size_t kZlibSlice = size_t{1} << 30;
// Deflate cannot compress better than about 1032:1; a larger ISIZE hint is a lie.
constexpr uint64_t kMaxDeflateRatio = 1032;

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};

// The gzip trailer's ISIZE (size mod 2^32 of the last member) sizes the first
// allocation; it is only a hint, trusted no further than deflate's best ratio.
size_t InitialOutputSize(const uint8_t* bytes, size_t size, uint64_t max_bytes) {
  uint64_t hint = 0;
  if (size >= 4) {
    for (int i = 0; i < 4; ++i) hint |= uint64_t{bytes[size - 4 + i]} << (8 * i);
  }
  hint = std::min({hint, uint64_t{size} * kMaxDeflateRatio, max_bytes});
  return static_cast<size_t>(std::max<uint64_t>(hint, 4096));
}

// Ends inflate state on every exit path.
struct InflateGuard {
  z_stream* stream;
  ~InflateGuard() { inflateEnd(stream); }
};

}  // namespace

bool IsGzip(const uint8_t* bytes, size_t size) {
  return size >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b;
}

StatusOr<std::vector<uint8_t>> InflateGzip(const uint8_t* bytes, size_t size, uint64_t max_bytes,
                                           const std::string& name) {
  z_stream zs{};
  // 16 + MAX_WBITS: expect a gzip wrapper (header and CRC are checked by zlib).
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) return InternalError(name + ": inflateInit2 failed");
  InflateGuard guard{&zs};
  std::vector<uint8_t> out(InitialOutputSize(bytes, size, max_bytes));
  size_t produced = 0;
  size_t consumed = 0;
  bool member_done = false;
  while (true) {
    if (produced == out.size()) {
      if (out.size() >= max_bytes) {
        return ResourceLimit(name + ": gzip data inflates beyond the limit of " +
                             std::to_string(max_bytes) + " bytes");
      }
      out.resize(static_cast<size_t>(std::min<uint64_t>(uint64_t{out.size()} * 2, max_bytes)));
    }
    const size_t in_slice = std::min(size - consumed, kZlibSlice);
    const size_t out_slice = std::min(out.size() - produced, kZlibSlice);
    zs.next_in = const_cast<Bytef*>(bytes + consumed);
    zs.avail_in = static_cast<uInt>(in_slice);
    zs.next_out = out.data() + produced;
    zs.avail_out = static_cast<uInt>(out_slice);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    consumed += in_slice - zs.avail_in;
    produced += out_slice - zs.avail_out;
    member_done = rc == Z_STREAM_END;
    if (member_done) {
      // Concatenated members are one file (RFC 1952 §2.2); trailing zeros are padding.
      const bool another = IsGzip(bytes + consumed, size - consumed);
      if (!another) break;
      if (inflateReset(&zs) != Z_OK) return InternalError(name + ": inflateReset failed");
      continue;
    }
    if (rc == Z_BUF_ERROR && consumed == size) break;  // input ran out mid-member
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      return ParseError(name + ": corrupt gzip data (" + (zs.msg ? zs.msg : "zlib error " + std::to_string(rc)) + ")");
    }
  }
  if (!member_done) return ParseError(name + ": gzip data is truncated");
  out.resize(produced);
  out.shrink_to_fit();
  return out;
}

StatusOr<std::vector<uint8_t>> ReadFileBytes(const std::string& path, uint64_t max_bytes, bool* was_gzip) {
  if (was_gzip) *was_gzip = false;
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode)) return IoError(path + ": not a regular file");
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    return ResourceLimit(path + ": file is " + std::to_string(st.st_size) + " bytes, limit is " +
                         std::to_string(max_bytes));
  }
  std::unique_ptr<FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::vector<uint8_t> bytes(static_cast<size_t>(st.st_size));
  const size_t got = bytes.empty() ? 0 : std::fread(bytes.data(), 1, bytes.size(), file.get());
  if (got != bytes.size()) return IoError(path + ": read failed after " + std::to_string(got) + " bytes");
  if (!IsGzip(bytes.data(), bytes.size())) return bytes;
  if (was_gzip) *was_gzip = true;
  return InflateGzip(bytes.data(), bytes.size(), max_bytes, path);
}

}  // namespace eqmesh

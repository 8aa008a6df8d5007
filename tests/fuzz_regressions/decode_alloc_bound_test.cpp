// The decoder's allocation bound (coding/decoder.h, "Bounded allocation"): headers
// and chunk fields that claim more than the stream holds are refused before any
// single allocation exceeds DecodeAllocationBound(stream bytes). Measured, not
// assumed: this executable replaces the global operator new with one that records
// the largest request made while a probe is armed (Draco's allocations included,
// libdraco resolves operator new to this definition too).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "codec/codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/encoder.h"
#include "coding/entropy/byte_io.h"
#include "coding/stream_header.h"

namespace {

std::atomic<bool> g_armed{false};
std::atomic<size_t> g_largest{0};

void* Allocate(size_t size, size_t alignment) {
  if (g_armed.load(std::memory_order_relaxed)) {
    size_t seen = g_largest.load(std::memory_order_relaxed);
    while (size > seen && !g_largest.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
    }
  }
  void* p = nullptr;
  if (alignment <= alignof(std::max_align_t)) {
    p = std::malloc(size == 0 ? 1 : size);
  } else if (posix_memalign(&p, alignment, size == 0 ? 1 : size) != 0) {
    p = nullptr;
  }
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void* AllocateNoThrow(size_t size, size_t alignment) noexcept {
  try {
    return Allocate(size, alignment);
  } catch (...) {
    return nullptr;
  }
}

constexpr size_t kDefault = alignof(std::max_align_t);

}  // namespace

void* operator new(size_t n) { return Allocate(n, kDefault); }
void* operator new[](size_t n) { return Allocate(n, kDefault); }
void* operator new(size_t n, const std::nothrow_t&) noexcept { return AllocateNoThrow(n, kDefault); }
void* operator new[](size_t n, const std::nothrow_t&) noexcept { return AllocateNoThrow(n, kDefault); }
void* operator new(size_t n, std::align_val_t a) { return Allocate(n, static_cast<size_t>(a)); }
void* operator new[](size_t n, std::align_val_t a) { return Allocate(n, static_cast<size_t>(a)); }
void* operator new(size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return AllocateNoThrow(n, static_cast<size_t>(a));
}
void* operator new[](size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return AllocateNoThrow(n, static_cast<size_t>(a));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

namespace eqmesh {
namespace {

using bitstream::CoderId;
using bitstream::TransformId;

// Largest single allocation while decoding `stream` (every option combination the
// fuzz target uses), and whether any decode succeeded.
struct Probe {
  size_t largest = 0;
  bool any_ok = false;
};

Probe Measure(const std::vector<uint8_t>& stream) {
  Probe probe;
  for (const bool truncated : {false, true}) {
    for (const bool semi : {false, true}) {
      DecodeOptions options;
      options.allow_truncated = truncated;
      g_largest.store(0);
      g_armed.store(true);
      bool ok = false;
      if (semi) {
        ok = DecodeSemiRegular(stream.data(), stream.size(), options).ok();
      } else {
        ok = Decode(stream.data(), stream.size(), options).ok();
      }
      g_armed.store(false);
      probe.largest = std::max(probe.largest, g_largest.load());
      probe.any_ok = probe.any_ok || ok;
    }
  }
  return probe;
}

std::vector<uint8_t> EncodeSample(CoderId coder, TransformId transform, bool kept, bool draco_base = false) {
  EncodeOptions options;
  options.draco_base = draco_base;
  options.lambda = 0.05;
  options.coder = coder;
  options.transform = transform;
  return Encode(kept ? testing::MakeBumpySphereWithKept(2) : testing::MakeBumpySphere(2), options).value();
}

struct Sample {
  const char* name;
  std::vector<uint8_t> bytes;
};

const std::vector<Sample>& Samples() {
  static const std::vector<Sample> samples = {
      {"eq", EncodeSample(CoderId::kEq, TransformId::kUnlifted, true)},
      {"eq_lifted", EncodeSample(CoderId::kEq, TransformId::kLifted, false)},
      {"zerotree", EncodeSample(CoderId::kZerotree, TransformId::kUnlifted, true)},
      {"uniform", EncodeSample(CoderId::kUniform, TransformId::kUnlifted, true)},
      {"eq_draco", EncodeSample(CoderId::kEq, TransformId::kUnlifted, true, true)},
      {"zt_draco", EncodeSample(CoderId::kZerotree, TransformId::kLifted, false, true)},
  };
  return samples;
}

bool HasDracoBase(const Sample& s) {
  return !ReadStreamInfo(s.bytes.data(), s.bytes.size()).value().has_compact_base;
}

// Rewrites the header (levels, chunk sizes) keeping the chunk bytes as given.
std::vector<uint8_t> Rebuild(const StreamHeader& h, const std::vector<uint8_t>& chunks) {
  std::vector<uint8_t> out = WriteStreamHeader(h);
  out.insert(out.end(), chunks.begin(), chunks.end());
  return out;
}

struct Parsed {
  StreamHeader header;
  std::vector<uint8_t> chunks;  // everything after the header
};

Parsed Parse(const std::vector<uint8_t>& stream) {
  size_t header_size = 0;
  Parsed p{ReadStreamHeader(stream.data(), stream.size(), &header_size).value(), {}};
  p.chunks.assign(stream.begin() + static_cast<std::ptrdiff_t>(header_size), stream.end());
  return p;
}

void ExpectWithinBound(const std::vector<uint8_t>& stream, const std::string& what, size_t* worst) {
  const Probe probe = Measure(stream);
  *worst = std::max(*worst, probe.largest);
  EXPECT_LE(probe.largest, DecodeAllocationBound(stream.size()))
      << what << ": " << stream.size() << "-byte stream, largest allocation " << probe.largest;
}

// The sample streams themselves: small levels, far inside the bound.
TEST(DecodeAllocBound, SampleStreams) {
  for (const Sample& s : Samples()) {
    const Probe probe = Measure(s.bytes);
    EXPECT_TRUE(probe.any_ok) << s.name;
    EXPECT_LE(probe.largest, DecodeAllocationBound(s.bytes.size())) << s.name;
    std::printf("[ alloc    ] %-9s valid %5zu bytes: largest allocation %zu\n", s.name, s.bytes.size(),
                probe.largest);
  }
}

// Header claiming up to 12 levels (the chunk table extended with filler chunks),
// each extra chunk empty, tiny or a few dozen bytes: refused level by level before
// the claimed levels are allocated.
TEST(DecodeAllocBound, HeaderClaimingMoreLevels) {
  for (const Sample& s : Samples()) {
    size_t worst = 0;
    const Parsed p = Parse(s.bytes);
    for (int levels = 3; levels <= bitstream::kMaxLevels; ++levels) {
      for (const uint64_t extra : {uint64_t{0}, uint64_t{1}, uint64_t{13}, uint64_t{64}}) {
        for (const uint8_t fill : {uint8_t{0x00}, uint8_t{0x5A}, uint8_t{0xFF}}) {
          StreamHeader h = p.header;
          const size_t old = h.level_sizes.size();
          h.levels = levels;
          h.level_sizes.resize(static_cast<size_t>(levels), extra);
          std::vector<uint8_t> chunks = p.chunks;
          chunks.resize(chunks.size() + (static_cast<size_t>(levels) - old) * extra, fill);
          ExpectWithinBound(Rebuild(h, chunks), std::string(s.name) + " claiming " + std::to_string(levels) +
                                                    " levels of " + std::to_string(extra) + " bytes",
                            &worst);
        }
      }
    }
    std::printf("[ alloc    ] %-9s more levels: largest allocation %zu\n", s.name, worst);
  }
}

// Chunk sizes up to the 4 GiB field limit with the bytes absent.
TEST(DecodeAllocBound, HeaderClaimingHugeChunks) {
  for (const Sample& s : Samples()) {
    size_t worst = 0;
    const Parsed p = Parse(s.bytes);
    for (const uint64_t size : {uint64_t{1} << 20, uint64_t{1} << 31, bitstream::kMaxChunkBytes}) {
      StreamHeader base = p.header;
      base.base_size = size;
      ExpectWithinBound(Rebuild(base, p.chunks), "base chunk", &worst);
      if (p.header.has_kept()) {
        StreamHeader kept = p.header;
        kept.kept_size = size;
        ExpectWithinBound(Rebuild(kept, p.chunks), "kept chunk", &worst);
      }
      for (size_t j = 0; j < p.header.level_sizes.size(); ++j) {
        StreamHeader level = p.header;
        level.level_sizes[j] = size;
        ExpectWithinBound(Rebuild(level, p.chunks), "level chunk " + std::to_string(j), &worst);
      }
    }
    std::printf("[ alloc    ] %-9s huge chunks: largest allocation %zu\n", s.name, worst);
  }
}

// The element counts inside the Draco base and kept chunks (vertices, faces,
// symbols, attribute sizes: wherever they sit): every byte of those chunks set to
// large values, and a 32-bit varint inserted at every position (chunk size in the
// header adjusted), so every count Draco reads can claim billions.
TEST(DecodeAllocBound, DracoChunksClaimingHugeCounts) {
  for (const Sample& s : Samples()) {
    if (!HasDracoBase(s)) continue;
    size_t worst = 0;
    const Parsed p = Parse(s.bytes);
    const size_t kept_begin = p.header.base_size;
    const size_t kept_end = kept_begin + p.header.kept_size;
    for (size_t at = 0; at < kept_end; ++at) {
      const bool in_base = at < kept_begin;
      for (const uint8_t value : {uint8_t{0xFF}, uint8_t{0x7F}, uint8_t{0x80}}) {
        std::vector<uint8_t> chunks = p.chunks;
        chunks[at] = value;
        ExpectWithinBound(Rebuild(p.header, chunks), "byte " + std::to_string(at) + " set", &worst);
      }
      for (const std::vector<uint8_t>& varint :
           {std::vector<uint8_t>{0xFF, 0xFF, 0xFF, 0xFF, 0x0F}, std::vector<uint8_t>{0xFF, 0xFF, 0xFF, 0x7F}}) {
        std::vector<uint8_t> chunks = p.chunks;
        chunks.insert(chunks.begin() + static_cast<std::ptrdiff_t>(at), varint.begin(), varint.end());
        StreamHeader h = p.header;
        (in_base ? h.base_size : h.kept_size) += varint.size();
        ExpectWithinBound(Rebuild(h, chunks), "varint inserted at byte " + std::to_string(at), &worst);
      }
    }
    std::printf("[ alloc    ] %-9s Draco fields: largest allocation %zu\n", s.name, worst);
  }
}

// Base chunk with its edgebreaker header rewritten (ext_spec A.3: "DRACO", version,
// type, method, flags, traversal, then varints num_encoded_vertices, num_faces, a
// byte, num_encoded_symbols, num_encoded_split_symbols) to declare `faces` faces and
// vertices; the rest of the chunk unchanged.
std::vector<uint8_t> WithDracoCounts(const Parsed& p, uint64_t faces) {
  const std::vector<uint8_t> base(p.chunks.begin(), p.chunks.begin() + static_cast<std::ptrdiff_t>(p.header.base_size));
  EXPECT_EQ(base[8], 1) << "the sample's base chunk is not edgebreaker";
  ByteReader r(base.data() + 12, base.size() - 12, "draco");
  uint64_t v = 0;
  uint8_t attribute_data = 0;
  EXPECT_TRUE(r.ReadVarint(&v).ok() && r.ReadVarint(&v).ok() && r.ReadU8(&attribute_data).ok() &&
              r.ReadVarint(&v).ok() && r.ReadVarint(&v).ok());
  ByteWriter w;
  w.PutBytes(base.data(), 12);
  w.PutVarint(faces);  // num_encoded_vertices
  w.PutVarint(faces);  // num_faces
  w.PutU8(attribute_data);
  w.PutVarint(faces);  // num_encoded_symbols
  w.PutVarint(0);      // num_encoded_split_symbols
  w.PutBytes(base.data() + 12 + r.offset(), base.size() - 12 - r.offset());
  std::vector<uint8_t> chunks = w.Take();
  chunks.insert(chunks.end(), p.chunks.begin() + static_cast<std::ptrdiff_t>(p.header.base_size), p.chunks.end());
  StreamHeader h = p.header;
  h.base_size = h.base_size - base.size() + (chunks.size() - (p.chunks.size() - base.size()));
  return Rebuild(h, chunks);
}

// Draco allocates for the counts of its connectivity header before reading the
// symbols behind them (a fuzzer-found 241-byte stream asked for 689 MB): counts up
// to the resource rule of ext_spec A.3 (2^17 + 64 per chunk byte) stay within the
// bound, larger ones are refused before Draco runs.
TEST(DecodeAllocBound, DracoHeaderCounts) {
  for (const Sample& s : Samples()) {
    if (!HasDracoBase(s)) continue;
    size_t worst = 0;
    const Parsed p = Parse(s.bytes);
    // The rewritten varints make the chunk up to 16 bytes longer: 64 * 16 of margin.
    const uint64_t rule = (uint64_t{1} << 17) + 64 * p.header.base_size;
    for (const uint64_t faces : {rule, rule + 1024, uint64_t{1} << 24, uint64_t{0xFFFFFFFF} / 3}) {
      const std::vector<uint8_t> stream = WithDracoCounts(p, faces);
      ExpectWithinBound(stream, std::to_string(faces) + " declared faces", &worst);
      const Status status = Decode(stream.data(), stream.size()).status();
      EXPECT_FALSE(status.ok());
      if (faces > rule) {
        EXPECT_EQ(status.code(), StatusCode::kResourceLimit) << status.ToString();
      }
    }
    std::printf("[ alloc    ] %-9s Draco counts: largest allocation %zu\n", s.name, worst);
  }
}

}  // namespace
}  // namespace eqmesh

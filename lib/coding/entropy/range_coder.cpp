// Range coder: see range_coder.h for the papers followed and the departures.
#include "coding/entropy/range_coder.h"

#include <cassert>

namespace eqmesh {
namespace {

constexpr uint32_t kTop = 1u << 24;  // renormalise when the range drops below this

}  // namespace

void AdaptiveBit::Update(int bit) {
  // Exponential forgetting with window ~2^kAdaptShift; p0 stays in [31, 4065].
  if (bit == 0) {
    p0_ += (kOne - p0_) >> kAdaptShift;
  } else {
    p0_ -= p0_ >> kAdaptShift;
  }
}

// ---- Encoder ---------------------------------------------------------------

void RangeEncoder::ShiftLow() {
  // A byte can leave the window only once no carry can reach it any more: either
  // the top byte of low is below 0xFF (a carry would stop inside it) or a carry
  // has just happened (bit 32 set).
  if (low_ < 0xFF000000ull || low_ > 0xFFFFFFFFull) {
    const uint8_t carry = static_cast<uint8_t>(low_ >> 32);
    uint8_t byte = cache_;
    for (; pending_ > 0; --pending_) {
      if (!first_) out_.push_back(static_cast<uint8_t>(byte + carry));
      first_ = false;
      byte = 0xFF;
    }
    cache_ = static_cast<uint8_t>(low_ >> 24);
  }
  ++pending_;
  low_ = (low_ & 0x00FFFFFFull) << 8;
}

void RangeEncoder::Normalize() {
  while (range_ < kTop) {
    range_ <<= 8;
    ShiftLow();
  }
}

void RangeEncoder::EncodeSymbol(uint32_t cum, uint32_t freq, int total_bits) {
  assert(total_bits >= 1 && total_bits <= 16);
  assert(freq >= 1 && cum + freq <= (1u << total_bits));
  const uint32_t r = range_ >> total_bits;
  low_ += static_cast<uint64_t>(cum) * r;
  range_ = freq * r;
  Normalize();
}

void RangeEncoder::EncodeBit(AdaptiveBit* model, int bit) {
  const uint32_t bound = (range_ >> AdaptiveBit::kProbBits) * model->p0();
  if (bit == 0) {
    range_ = bound;
  } else {
    low_ += bound;
    range_ -= bound;
  }
  model->Update(bit);
  Normalize();
}

void RangeEncoder::EncodeBits(uint32_t value, int n) {
  assert(n >= 0 && n <= 32);
  while (n > 0) {
    const int chunk = n > 16 ? 16 : n;
    n -= chunk;
    EncodeSymbol((value >> n) & ((1u << chunk) - 1), 1, chunk);
  }
}

void RangeEncoder::EncodeExpGolomb(uint32_t value, int k) {
  const uint64_t x = static_cast<uint64_t>(value) + (1ull << k);
  int bits = 0;
  while ((x >> bits) > 1) ++bits;  // bits = floor(log2 x)
  const int zeros = bits - k;
  // One call per prefix bit: the decoder reads the prefix bit by bit, and a 16-bit
  // symbol does not split the range exactly like 16 one-bit symbols.
  for (int i = 0; i < zeros; ++i) EncodeBits(0, 1);
  EncodeBits(1, 1);
  // The low `bits` bits follow the leading one; split so each call stays <= 32.
  const uint64_t rest = x & ((1ull << bits) - 1);
  if (bits > 32) EncodeBits(static_cast<uint32_t>(rest >> 32), bits - 32);
  EncodeBits(static_cast<uint32_t>(rest & 0xFFFFFFFFull), bits > 32 ? 32 : bits);
}

std::vector<uint8_t> RangeEncoder::Finish() {
  // Five shifts push the 32 bits of low plus the cache byte out; the decoder then
  // sees the exact code value without reading past the end.
  for (int i = 0; i < 5; ++i) ShiftLow();
  return std::move(out_);
}

// ---- Decoder ---------------------------------------------------------------

RangeDecoder::RangeDecoder(const uint8_t* data, size_t size) : data_(data), size_(size) {
  for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | NextByte();
}

Status RangeDecoder::CheckConsumedAll(const std::string& where) const {
  if (ConsumedAll()) return Status::Ok();
  return CorruptStream(where + ": " + std::to_string(size_ - pos_) + " bytes left over after its last symbol");
}

uint8_t RangeDecoder::NextByte() {
  if (pos_ >= size_ || data_ == nullptr) {
    error_ = true;
    ++pos_;
    return 0;
  }
  return data_[pos_++];
}

void RangeDecoder::Normalize() {
  while (range_ < kTop) {
    range_ <<= 8;
    code_ = (code_ << 8) | NextByte();
  }
}

uint32_t RangeDecoder::DecodeFreq(int total_bits) {
  assert(total_bits >= 1 && total_bits <= 16);
  pending_shift_ = total_bits;
  const uint32_t r = range_ >> total_bits;
  const uint32_t total = 1u << total_bits;
  uint32_t v = code_ / r;
  if (v >= total) {  // only reachable on a stream no encoder wrote
    error_ = true;
    v = total - 1;
  }
  return v;
}

void RangeDecoder::Consume(uint32_t cum, uint32_t freq) {
  const uint32_t r = range_ >> pending_shift_;
  const uint64_t base = static_cast<uint64_t>(cum) * r;
  if (base > code_) {  // caller passed an interval not containing the code
    error_ = true;
    code_ = 0;
  } else {
    code_ -= static_cast<uint32_t>(base);
  }
  range_ = freq * r;
  if (range_ == 0) {
    error_ = true;
    range_ = kTop;
  }
  Normalize();
}

int RangeDecoder::DecodeBit(AdaptiveBit* model) {
  const uint32_t bound = (range_ >> AdaptiveBit::kProbBits) * model->p0();
  int bit;
  if (code_ < bound) {
    range_ = bound;
    bit = 0;
  } else {
    code_ -= bound;
    range_ -= bound;
    bit = 1;
  }
  model->Update(bit);
  Normalize();
  return bit;
}

uint32_t RangeDecoder::DecodeBits(int n) {
  assert(n >= 0 && n <= 32);
  uint32_t value = 0;
  while (n > 0) {
    const int chunk = n > 16 ? 16 : n;
    n -= chunk;
    const uint32_t v = DecodeFreq(chunk);
    Consume(v, 1);
    value = (value << chunk) | v;
  }
  return value;
}

uint32_t RangeDecoder::DecodeExpGolomb(int k, int max_prefix) {
  int zeros = 0;
  while (DecodeBits(1) == 0) {
    if (++zeros > max_prefix || !ok()) {
      error_ = true;
      return 0;
    }
  }
  const int bits = zeros + k;
  uint64_t rest = 0;
  if (bits > 32) rest = static_cast<uint64_t>(DecodeBits(bits - 32)) << 32;
  rest |= DecodeBits(bits > 32 ? 32 : bits);
  const uint64_t x = (1ull << bits) | rest;
  const uint64_t v = x - (1ull << k);
  if (v > 0xFFFFFFFFull) {
    error_ = true;
    return 0;
  }
  return static_cast<uint32_t>(v);
}

}  // namespace eqmesh

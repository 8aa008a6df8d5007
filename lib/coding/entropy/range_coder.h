// Range coder (Martin 1979, "Range encoding"; arithmetic coding after Witten, Neal,
// Cleary 1987, CACM 30(6)). 32-bit range, byte-wise output with a cache byte and a
// pending-0xFF count for carry propagation, so the encoder never has to revisit
// bytes it already wrote.
//
// Departures: totals are powers of two (2^total_bits, at most 2^16) so the coder
// divides by shifting; the adaptive binary model is a 12-bit probability updated by
// shifting (no counts); bypass bits and order-k Exp-Golomb codes are built on top.
//
// The decoder never reads outside its byte span: a read past the end returns zero
// and sets a sticky error flag that callers check with ok() before trusting output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace eqmesh {

// Adaptive probability of a binary event; both coder sides update it identically.
class AdaptiveBit {
 public:
  static constexpr int kProbBits = 12;
  static constexpr uint32_t kOne = 1u << kProbBits;
  // Probability (in 1/4096) that the next bit is 0.
  uint32_t p0() const { return p0_; }
  void Update(int bit);

 private:
  static constexpr int kAdaptShift = 5;
  uint32_t p0_ = kOne / 2;
};

class RangeEncoder {
 public:
  RangeEncoder() = default;

  // Codes the interval [cum, cum + freq) of a total of 2^total_bits.
  // Preconditions (asserted by the caller): freq >= 1, cum + freq <= 2^total_bits,
  // total_bits <= 16.
  void EncodeSymbol(uint32_t cum, uint32_t freq, int total_bits);
  void EncodeBit(AdaptiveBit* model, int bit);
  // n raw bits of value (n <= 32), most significant first.
  void EncodeBits(uint32_t value, int n);
  // Order-k Exp-Golomb code of value, all bits bypass.
  void EncodeExpGolomb(uint32_t value, int k);

  // Flushes and returns the bytes; the encoder must not be used afterwards.
  std::vector<uint8_t> Finish();

 private:
  void ShiftLow();
  void Normalize();

  uint64_t low_ = 0;  // 33 significant bits: bit 32 is the carry
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t pending_ = 1;  // cache byte + pending 0xFF bytes not yet written
  bool first_ = true;     // the very first cache byte is a placeholder, never emitted
  std::vector<uint8_t> out_;
};

class RangeDecoder {
 public:
  RangeDecoder(const uint8_t* data, size_t size);

  // Returns the cumulative frequency the next symbol falls in; the caller finds the
  // symbol (cum, freq) containing it and calls Consume. Always < 2^total_bits.
  uint32_t DecodeFreq(int total_bits);
  void Consume(uint32_t cum, uint32_t freq);
  int DecodeBit(AdaptiveBit* model);
  uint32_t DecodeBits(int n);
  // Exp-Golomb with at most max_prefix leading zeros; longer prefixes set the error.
  uint32_t DecodeExpGolomb(int k, int max_prefix = 24);

  // False once the decoder read past the end of its input or met an impossible
  // code value; sticky.
  bool ok() const { return !error_; }
  void SetError() { error_ = true; }
  // Bytes consumed so far (may exceed size only when !ok()).
  size_t position() const { return pos_; }
  // Whether every byte of the input was consumed: a chunk the encoder finished
  // holds exactly 4 + (renormalisation shifts) bytes (ext_spec A.4.1), so bytes
  // left over after its last symbol mean a corrupt or padded chunk.
  bool ConsumedAll() const { return pos_ == size_; }
  // Ok when ConsumedAll(); else a corrupt-stream error naming `where` and the
  // bytes left over.
  Status CheckConsumedAll(const std::string& where) const;

 private:
  uint8_t NextByte();
  void Normalize();

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  int pending_shift_ = 0;  // total_bits of the DecodeFreq awaiting Consume
  bool error_ = false;
};

}  // namespace eqmesh

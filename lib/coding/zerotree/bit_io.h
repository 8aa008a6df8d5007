// Binary symbol sinks/sources of the zerotree coder on top of the project's range
// coder (coding/entropy/range_coder.h: Martin 1979; Witten, Neal, Cleary 1987).
//
// Embedded-stream support, a departure from plain range coding:
//  * BudgetedEncoder refuses the first symbol that would make the finished stream
//    exceed its byte budget. It shadows the coder's range register to know the
//    finished size before coding (the coder's output is 4 bytes + one byte per
//    renormalisation shift); the caller checks the real size afterwards.
//  * PrefixDecoder decodes a possibly truncated payload twice in lock step, once
//    padded with 0x00 and once with 0xFF bytes. Every continuation of the prefix
//    lies between the two, and the set of code values giving one symbol sequence
//    is an interval, so while both agree the symbol is the one the encoder wrote;
//    the first disagreement ends decoding (no symbol is guessed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/entropy/range_coder.h"

namespace eqmesh::zerotree {

class BudgetedEncoder {
 public:
  // budget_bytes: most bytes the payload plus the header may take (0 = no limit);
  // header_bytes(count) gives the header size for a stream of `count` symbols.
  BudgetedEncoder(size_t num_contexts, uint64_t budget_bytes, size_t (*header_bytes)(uint64_t),
                  uint64_t symbol_limit);

  // Codes *bit with the adaptive model `ctx`; false (nothing coded) when refused.
  bool Bit(int ctx, int* bit);
  // Codes *bit with probability 1/2.
  bool Raw(int* bit);

  uint64_t symbols() const { return count_; }
  // Payload bytes the finished stream will have (exact for the current coder).
  uint64_t predicted_bytes() const { return count_ == 0 ? 0 : shifts_ + 4; }
  std::vector<uint8_t> Finish();

 private:
  bool Admit(uint32_t next_range);

  RangeEncoder encoder_;
  std::vector<AdaptiveBit> models_;
  uint64_t budget_;
  size_t (*header_bytes_)(uint64_t);
  uint64_t limit_;
  uint64_t count_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;  // shadow of the coder's range register
  uint64_t shifts_ = 0;           // renormalisation byte shifts so far
};

class PrefixDecoder {
 public:
  // data/size: the payload (possibly truncated); symbol_limit: symbols the encoder
  // wrote (from the stream header).
  PrefixDecoder(size_t num_contexts, const uint8_t* data, size_t size, uint64_t symbol_limit);

  // False once the stream is exhausted or ambiguous; *bit untouched then.
  bool Bit(int ctx, int* bit);
  bool Raw(int* bit);
  bool exhausted() const { return stopped_; }
  uint64_t symbols() const { return count_; }

 private:
  bool Accept(int low_bit, int high_bit, int* bit);

  static constexpr size_t kPadding = 16;
  std::vector<uint8_t> low_bytes_, high_bytes_;  // payload + 0x00 / 0xFF padding
  RangeDecoder low_, high_;
  std::vector<AdaptiveBit> low_models_, high_models_;
  uint64_t limit_;
  uint64_t count_ = 0;
  bool stopped_ = false;
};

}  // namespace eqmesh::zerotree

// Zerotree symbol I/O: see bit_io.h for the papers followed and the departures.
#include "coding/zerotree/bit_io.h"

namespace eqmesh::zerotree {
namespace {

constexpr uint32_t kTop = 1u << 24;  // the range coder renormalises below this

uint64_t ShiftsToNormalize(uint32_t* range) {
  uint64_t shifts = 0;
  while (*range < kTop) {
    *range <<= 8;
    ++shifts;
  }
  return shifts;
}

std::vector<uint8_t> Padded(const uint8_t* data, size_t size, size_t padding, uint8_t fill) {
  std::vector<uint8_t> out(size + padding, fill);
  for (size_t i = 0; i < size; ++i) out[i] = data[i];
  return out;
}

}  // namespace

BudgetedEncoder::BudgetedEncoder(size_t num_contexts, uint64_t budget_bytes,
                                 size_t (*header_bytes)(uint64_t), uint64_t symbol_limit)
    : models_(num_contexts), budget_(budget_bytes), header_bytes_(header_bytes), limit_(symbol_limit) {}

bool BudgetedEncoder::Admit(uint32_t next_range) {
  if (count_ >= limit_) return false;
  const uint64_t next_shifts = shifts_ + ShiftsToNormalize(&next_range);
  if (budget_ != 0 && header_bytes_(count_ + 1) + next_shifts + 4 > budget_) {
    limit_ = count_;  // embedded: once refused, every later symbol is refused too
    return false;
  }
  range_ = next_range;
  shifts_ = next_shifts;
  ++count_;
  return true;
}

bool BudgetedEncoder::Bit(int ctx, int* bit) {
  AdaptiveBit* model = &models_[static_cast<size_t>(ctx)];
  const uint32_t bound = (range_ >> AdaptiveBit::kProbBits) * model->p0();
  if (!Admit(*bit ? range_ - bound : bound)) return false;
  encoder_.EncodeBit(model, *bit);
  return true;
}

bool BudgetedEncoder::Raw(int* bit) {
  if (!Admit(range_ >> 1)) return false;
  encoder_.EncodeBits(static_cast<uint32_t>(*bit), 1);
  return true;
}

std::vector<uint8_t> BudgetedEncoder::Finish() {
  if (count_ == 0) return {};  // an empty payload decodes to "no symbols"
  return encoder_.Finish();
}

PrefixDecoder::PrefixDecoder(size_t num_contexts, const uint8_t* data, size_t size, uint64_t symbol_limit)
    : low_bytes_(Padded(data, size, kPadding, 0x00)),
      high_bytes_(Padded(data, size, kPadding, 0xFF)),
      low_(low_bytes_.data(), low_bytes_.size()),
      high_(high_bytes_.data(), high_bytes_.size()),
      low_models_(num_contexts),
      high_models_(num_contexts),
      limit_(symbol_limit) {
  if (size == 0) stopped_ = true;
}

bool PrefixDecoder::Accept(int low_bit, int high_bit, int* bit) {
  // A decoder that read past its padding no longer brackets the true code value.
  if (low_bit != high_bit || !low_.ok() || !high_.ok()) {
    stopped_ = true;
    return false;
  }
  *bit = low_bit;
  ++count_;
  return true;
}

bool PrefixDecoder::Bit(int ctx, int* bit) {
  if (stopped_ || count_ >= limit_) return false;
  const size_t c = static_cast<size_t>(ctx);
  const int a = low_.DecodeBit(&low_models_[c]);
  const int b = high_.DecodeBit(&high_models_[c]);
  return Accept(a, b, bit);
}

bool PrefixDecoder::Raw(int* bit) {
  if (stopped_ || count_ >= limit_) return false;
  const int a = static_cast<int>(low_.DecodeBits(1));
  const int b = static_cast<int>(high_.DecodeBits(1));
  return Accept(a, b, bit);
}

}  // namespace eqmesh::zerotree

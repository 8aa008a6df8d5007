// EQ level decoder: see eq_decoder.h and eq_model.h for papers and departures.
#include "coding/eq/eq_decoder.h"

#include <string>

#include "coding/eq/eq_model.h"
#include "coding/entropy/range_coder.h"

namespace eqmesh {

int64_t PeekEqLevelCount(const uint8_t* data, size_t size) {
  RangeDecoder dec(data, size);
  const uint32_t count = dec.DecodeBits(32);
  return dec.ok() ? int64_t{count} : -1;
}

namespace {

// Normal indices of every vertex, in scan order.
std::vector<int64_t> DecodeNormalStream(const EqLevelLayout& layout, const EqSideInfo& side,
                                        RangeDecoder* dec, EqEscapeModels* models) {
  const EqContextTerms terms(layout, false);
  std::vector<int64_t> normal(layout.size(), 0);
  for (size_t i = 0; i < normal.size() && dec->ok(); ++i) {
    const EqChoice c = ChooseQuantizer(side, normal.data(), terms, i);
    normal[i] = ReconstructIndex(c.quantizer, DecodeIndex(dec, c.quantizer, c.ctx, models));
  }
  return normal;
}

// (tangent, bitangent) of every vertex, in scan order: value 2i + c.
std::vector<int64_t> DecodeTangentialStream(const EqLevelLayout& layout, const EqSideInfo& side,
                                            RangeDecoder* dec, EqEscapeModels* models) {
  std::vector<int64_t> tangential(2 * layout.size(), 0);
  if (!side.tangential_context) {
    const EqQuantizer tq = TangentialQuantizer(side);
    for (size_t p = 0; p < tangential.size() && dec->ok(); ++p) {
      tangential[p] = ReconstructIndex(tq, DecodeIndex(dec, tq, EqContext::kTangential, models));
    }
    return tangential;
  }
  const EqContextTerms terms(layout, true);
  for (size_t p = 0; p < tangential.size() && dec->ok(); ++p) {
    const EqChoice c = ChooseQuantizer(side, tangential.data(), terms, p);
    tangential[p] = ReconstructIndex(c.quantizer, DecodeIndex(dec, c.quantizer, c.ctx, models));
  }
  return tangential;
}

}  // namespace

StatusOr<bool> EqLevelCodesNothing(const uint8_t* data, size_t size, uint32_t count, bool tangential_context,
                                   int level) {
  RangeDecoder dec(data, size);
  EqSideInfo side;
  if (!DecodeSideInfo(&dec, count, tangential_context, &side)) return false;
  if (!UnpredictableQuantizer(side, false).codes_nothing() || !UnpredictableQuantizer(side, true).codes_nothing()) {
    return false;
  }
  EQMESH_RETURN_IF_ERROR(dec.CheckConsumedAll("EQ level " + std::to_string(level)));
  return true;
}

StatusOr<std::vector<std::array<int64_t, 3>>> DecodeEqLevelQuanta(const EqLevelLayout& layout,
                                                                 const uint8_t* data, size_t size,
                                                                 bool tangential_context) {
  const std::string where = "EQ level " + std::to_string(layout.level);
  RangeDecoder dec(data, size);
  EqSideInfo side;
  if (!DecodeSideInfo(&dec, static_cast<uint32_t>(layout.size()), tangential_context, &side)) {
    return CorruptStream(where + ": invalid or truncated side information");
  }
  EqEscapeModels models;
  const std::vector<int64_t> normal = DecodeNormalStream(layout, side, &dec, &models);
  const std::vector<int64_t> tangential = DecodeTangentialStream(layout, side, &dec, &models);
  if (!dec.ok()) return CorruptStream(where + ": coefficient data truncated or corrupt");
  EQMESH_RETURN_IF_ERROR(dec.CheckConsumedAll(where));
  std::vector<std::array<int64_t, 3>> out(layout.size());
  for (size_t i = 0; i < layout.size(); ++i) {
    out[layout.scan[i]] = {normal[i], tangential[2 * i], tangential[2 * i + 1]};
  }
  return out;
}

StatusOr<std::vector<Vec3>> DecodeEqLevel(const EqLevelLayout& layout, const uint8_t* data,
                                          size_t size, double q0, bool tangential_context) {
  using Quanta = std::vector<std::array<int64_t, 3>>;
  EQMESH_ASSIGN_OR_RETURN(Quanta quanta, DecodeEqLevelQuanta(layout, data, size, tangential_context));
  std::vector<Vec3> out(quanta.size());
  for (size_t k = 0; k < quanta.size(); ++k) {
    out[k] = Vec3(static_cast<double>(quanta[k][0]) * q0, static_cast<double>(quanta[k][1]) * q0,
                  static_cast<double>(quanta[k][2]) * q0);
  }
  return out;
}

}  // namespace eqmesh

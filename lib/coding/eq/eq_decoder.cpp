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

StatusOr<std::vector<std::array<int64_t, 3>>> DecodeEqLevelQuanta(const EqLevelLayout& layout,
                                                                 const uint8_t* data, size_t size) {
  const std::string where = "EQ level " + std::to_string(layout.level);
  RangeDecoder dec(data, size);
  EqSideInfo side;
  if (!DecodeSideInfo(&dec, static_cast<uint32_t>(layout.size()), &side)) {
    return CorruptStream(where + ": invalid or truncated side information");
  }
  const size_t n = layout.size();
  std::vector<int64_t> normal(n, 0);
  EqEscapeModels models;
  for (size_t i = 0; i < n && dec.ok(); ++i) {
    const uint32_t begin = layout.offsets[i];
    const EqNormalChoice c = ChooseNormalQuantizer(side, normal.data(), &layout.neighbours[begin],
                                                   &layout.ring[begin], layout.offsets[i + 1] - begin);
    normal[i] = ReconstructIndex(c.quantizer, DecodeIndex(&dec, c.quantizer, c.ctx, &models));
  }
  std::vector<std::array<int64_t, 3>> out(n, {0, 0, 0});
  const EqQuantizer tq = TangentialQuantizer(side);
  for (size_t i = 0; i < n && dec.ok(); ++i) {
    std::array<int64_t, 3>& v = out[layout.scan[i]];
    v[0] = normal[i];
    for (int c = 1; c < 3; ++c) {
      v[c] = ReconstructIndex(tq, DecodeIndex(&dec, tq, EqContext::kTangential, &models));
    }
  }
  if (!dec.ok()) return CorruptStream(where + ": coefficient data truncated or corrupt");
  return out;
}

StatusOr<std::vector<Vec3>> DecodeEqLevel(const EqLevelLayout& layout, const uint8_t* data,
                                          size_t size, double q0) {
  using Quanta = std::vector<std::array<int64_t, 3>>;
  EQMESH_ASSIGN_OR_RETURN(Quanta quanta, DecodeEqLevelQuanta(layout, data, size));
  std::vector<Vec3> out(quanta.size());
  for (size_t k = 0; k < quanta.size(); ++k) {
    out[k] = Vec3(static_cast<double>(quanta[k][0]) * q0, static_cast<double>(quanta[k][1]) * q0,
                  static_cast<double>(quanta[k][2]) * q0);
  }
  return out;
}

}  // namespace eqmesh

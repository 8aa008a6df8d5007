// Compact base-mesh chunk, the part both sides share: see compact_base_model.h.
#include "coding/compact_base/compact_base_model.h"

#include <algorithm>
#include <cmath>

namespace eqmesh {

Vec3 CompactGrid::Position(const std::array<int32_t, 3>& q) const {
  const double s = static_cast<double>(step);
  return Vec3(static_cast<double>(origin[0]) + static_cast<double>(q[0]) * s,
              static_cast<double>(origin[1]) + static_cast<double>(q[1]) * s,
              static_cast<double>(origin[2]) + static_cast<double>(q[2]) * s);
}

std::array<int32_t, 3> QuantizeToGrid(const CompactGrid& grid, const Vec3& p) {
  std::array<int32_t, 3> q{};
  for (size_t k = 0; k < 3; ++k) {
    const double v = (p[static_cast<int>(k)] - static_cast<double>(grid.origin[k])) / static_cast<double>(grid.step);
    q[k] = static_cast<int32_t>(std::clamp<double>(std::round(v), 0.0, grid.MaxIndex()));
  }
  return q;
}

uint32_t CompactBaseState::EdgeFaces(uint32_t u, uint32_t v) const {
  const auto it = edge_faces_.find(CompactEdgeKey(u, v));
  return it == edge_faces_.end() ? 0u : it->second;
}

bool CompactBaseState::AddFace(uint32_t a, uint32_t b, uint32_t c) {
  if (a == b || b == c || c == a) return false;
  const uint32_t corners[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    if (EdgeFaces(corners[k], corners[(k + 1) % 3]) >= 2) return false;
  }
  for (int k = 0; k < 3; ++k) {
    const uint32_t u = corners[k], v = corners[(k + 1) % 3];
    uint8_t& count = edge_faces_[CompactEdgeKey(u, v)];
    if (count++ == 0) {
      neighbours_[u].push_back(v);
      neighbours_[v].push_back(u);
    }
    gates_.push_back({u, v, corners[(k + 2) % 3]});
    ++faces_around_[u];
  }
  faces_.push_back({a, b, c});
  return true;
}

bool CompactBaseState::NextGate(CompactGate* gate) {
  while (!gates_.empty()) {
    *gate = gates_.front();
    gates_.pop_front();
    if (EdgeFaces(gate->a, gate->b) == 1) return true;
  }
  return false;
}

void CompactBaseState::AddToList(uint32_t from, uint32_t skip_a, uint32_t skip_b,
                                 std::vector<uint32_t>* out) const {
  for (const uint32_t x : neighbours_[from]) {
    if (x == skip_a || x == skip_b || EdgeFaces(from, x) != 1) continue;
    if (std::find(out->begin(), out->end(), x) == out->end()) out->push_back(x);
  }
}

void CompactBaseState::Candidates(uint32_t a, uint32_t b, std::vector<uint32_t>* out) const {
  out->clear();
  AddToList(a, a, b, out);
  AddToList(b, a, b, out);
}

std::array<int32_t, 3> ParallelogramPrediction(const CompactGrid& grid, const std::array<int32_t, 3>& a,
                                               const std::array<int32_t, 3>& b,
                                               const std::array<int32_t, 3>& c) {
  std::array<int32_t, 3> p{};
  for (int k = 0; k < 3; ++k) {
    const int64_t v = int64_t{a[k]} + b[k] - c[k];
    p[k] = static_cast<int32_t>(std::clamp<int64_t>(v, 0, grid.MaxIndex()));
  }
  return p;
}

std::array<int32_t, 3> SeedPrediction(const CompactGrid& grid, const std::vector<std::array<int32_t, 3>>& coded) {
  if (!coded.empty()) return coded.back();
  const int32_t centre = static_cast<int32_t>(int64_t{1} << (grid.bits - 1));
  return {centre, centre, centre};
}

int IndexBits(uint64_t count) {
  int bits = 0;
  while (bits < 63 && (uint64_t{1} << bits) < count) ++bits;
  return bits;
}

// Zero flag, bypass sign, then |r| as an Exp-Golomb code of order 0 whose prefix
// bits are adaptive (one model per prefix position) and whose suffix is bypass.
void EncodeResidual(RangeEncoder* enc, CompactResidualModels* models, int64_t r) {
  enc->EncodeBit(&models->zero, r != 0);
  if (r == 0) return;
  enc->EncodeBits(r < 0 ? 1u : 0u, 1);
  const uint64_t v = static_cast<uint64_t>(r < 0 ? -r : r);  // >= 1
  int p = 0;
  while ((v >> (p + 1)) != 0) ++p;
  for (int i = 0; i < p; ++i) enc->EncodeBit(&models->prefix[static_cast<size_t>(i)], 1);
  enc->EncodeBit(&models->prefix[static_cast<size_t>(p)], 0);
  if (p > 0) enc->EncodeBits(static_cast<uint32_t>(v - (uint64_t{1} << p)), p);
}

int64_t DecodeResidual(RangeDecoder* dec, CompactResidualModels* models) {
  if (dec->DecodeBit(&models->zero) == 0) return 0;
  const bool negative = dec->DecodeBits(1) != 0;
  int p = 0;
  while (dec->DecodeBit(&models->prefix[static_cast<size_t>(p)]) != 0) {
    if (++p > kCompactMaxPrefix || !dec->ok()) {
      dec->SetError();
      return 0;
    }
  }
  const int64_t v = (int64_t{1} << p) + (p > 0 ? static_cast<int64_t>(dec->DecodeBits(p)) : 0);
  return negative ? -v : v;
}

size_t GateContext(const CompactBaseState& state, const CompactGate& gate) {
  const auto capped = [&](uint32_t v) { return std::min<size_t>(state.FacesAround(v), kGateFanCap); };
  return capped(gate.a) * (kGateFanCap + 1) + capped(gate.b);
}

AdaptiveBit* GateIsNewModel(CompactModels* models, CompactLayout layout, const CompactBaseState& state,
                            const CompactGate& gate) {
  if (layout == CompactLayout::kInterleaved) return &models->is_new;
  return &models->gate_is_new[GateContext(state, gate)];
}

void EncodeCandidateIndex(RangeEncoder* enc, CompactModels* models, CompactLayout layout, size_t context,
                          uint64_t k, uint64_t count) {
  if (layout == CompactLayout::kInterleaved || count <= 1) {
    const int bits = IndexBits(count);
    if (bits > 0) enc->EncodeBits(static_cast<uint32_t>(k), bits);
    return;
  }
  enc->EncodeBit(&models->gate_first_candidate[context], k == 0);
  for (uint64_t j = 1; j < kUnaryCandidates && j + 1 < count; ++j) {
    if (k < j) return;
    enc->EncodeBit(&models->later_candidate[j - 1], k == j);
  }
  if (k >= kUnaryCandidates && count > kUnaryCandidates) {
    const int bits = IndexBits(count - kUnaryCandidates);
    if (bits > 0) enc->EncodeBits(static_cast<uint32_t>(k - kUnaryCandidates), bits);
  }
}

bool DecodeCandidateIndex(RangeDecoder* dec, CompactModels* models, CompactLayout layout, size_t context,
                          uint64_t count, uint64_t* k) {
  if (layout == CompactLayout::kInterleaved || count <= 1) {
    const int bits = IndexBits(count);
    *k = bits > 0 ? dec->DecodeBits(bits) : 0;
    return *k < count;
  }
  if (dec->DecodeBit(&models->gate_first_candidate[context]) != 0) {
    *k = 0;
    return true;
  }
  uint64_t j = 1;
  for (; j < kUnaryCandidates && j + 1 < count; ++j) {
    if (dec->DecodeBit(&models->later_candidate[j - 1]) != 0) {
      *k = j;
      return true;
    }
  }
  if (j < kUnaryCandidates) {  // the unary steps ran out at the last candidate
    *k = j;
    return true;
  }
  const int bits = IndexBits(count - kUnaryCandidates);
  *k = kUnaryCandidates + (bits > 0 ? dec->DecodeBits(bits) : 0);
  return *k < count;
}

}  // namespace eqmesh

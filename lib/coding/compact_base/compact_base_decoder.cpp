// Compact base-mesh chunk decoder: see compact_base_decoder.h and compact_base_model.h.
#include "coding/compact_base/compact_base_decoder.h"

#include <algorithm>

#include "coding/compact_base/compact_base_model.h"
#include "coding/compact_base/compact_positions.h"
#include "coding/entropy/byte_io.h"

namespace eqmesh {
namespace {

struct ChunkHead {
  uint32_t vertices = 0;
  uint64_t faces = 0;
  CompactPositionCoding coding;
};

Status ReadChunkHead(ByteReader* r, uint32_t max_vertices, CompactLayout layout, ChunkHead* head) {
  uint64_t v = 0;
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(max_vertices, "vertex count", &v));
  if (v < 3) return r->Corrupt("fewer than 3 vertices");
  head->vertices = static_cast<uint32_t>(v);
  const uint64_t max_faces = kCompactMaxFacesPerVertex * v + kCompactFaceSlack;
  EQMESH_RETURN_IF_ERROR(r->ReadBoundedVarint(max_faces, "face count", &head->faces));
  if (head->faces == 0) return r->Corrupt("no faces");
  uint8_t bits = 0;
  EQMESH_RETURN_IF_ERROR(r->ReadU8(&bits));
  if (bits < 1 || bits > kCompactMaxBits) return r->Corrupt("quantization depth out of range");
  CompactGrid& grid = head->coding.grid;
  grid.bits = bits;
  for (float& o : grid.origin) EQMESH_RETURN_IF_ERROR(r->ReadFiniteF32(&o));
  EQMESH_RETURN_IF_ERROR(r->ReadFiniteF32(&grid.step));
  if (!(grid.step > 0.0f)) return r->Corrupt("quantization step must be positive");
  if (layout == CompactLayout::kPositionsAfter) {
    uint8_t quarters = 0;
    EQMESH_RETURN_IF_ERROR(r->ReadU8(&quarters));
    if (quarters == kGridChoiceModeByte) {
      head->coding.parallelogram_choice = true;
      quarters = kGridTangentialQuarters;
    }
    if (quarters < kGridTangentialQuarters) return r->Corrupt("tangential step below the grid step");
    head->coding.tangential_quarters = quarters;
  }
  return Status::Ok();
}

// The symbols of one chunk, read in the order the encoder wrote them.
class ChunkReader {
 public:
  ChunkReader(const ChunkHead& head, const uint8_t* data, size_t size, CompactLayout layout)
      : head_(head), layout_(layout), dec_(data, size), state_(head.vertices) {}

  // False on any inconsistency (the caller reports it as corrupt).
  bool Run() {
    while (dec_.ok() && dec_.DecodeBit(&models_.more_components) != 0) {
      if (!SeedComponent() || !GrowComponent()) return false;
    }
    if (layout_ == CompactLayout::kPositionsAfter && dec_.ok() && quanta_.size() == head_.vertices &&
        !DecodeCompactPositions(&dec_, head_.coding, state_.faces(), head_.vertices, &positions_)) {
      return false;
    }
    return dec_.ok() && dec_.ConsumedAll() && state_.faces().size() == head_.faces &&
           quanta_.size() == head_.vertices;
  }

  Mesh TakeMesh() {
    Mesh mesh;
    if (layout_ == CompactLayout::kPositionsAfter) {
      mesh.positions = std::move(positions_);
    } else {
      mesh.positions.reserve(quanta_.size());
      for (const auto& q : quanta_) mesh.positions.push_back(head_.coding.grid.Position(q));
    }
    mesh.faces = state_.faces();
    return mesh;
  }

 private:
  bool NewVertex(const std::array<int32_t, 3>& prediction, CompactResidualModels* models, uint32_t* id) {
    if (quanta_.size() >= head_.vertices) return false;
    std::array<int32_t, 3> q{};
    for (int k = 0; k < 3 && layout_ == CompactLayout::kInterleaved; ++k) {
      const int64_t v = int64_t{prediction[static_cast<size_t>(k)]} + DecodeResidual(&dec_, models);
      if (v < 0 || v > head_.coding.grid.MaxIndex()) return false;
      q[static_cast<size_t>(k)] = static_cast<int32_t>(v);
    }
    *id = static_cast<uint32_t>(quanta_.size());
    quanta_.push_back(q);
    return dec_.ok();
  }

  bool GlobalIndex(uint32_t* id) {
    const uint64_t n = quanta_.size();
    if (n == 0) return false;
    const int bits = IndexBits(n);
    const uint64_t v = bits > 0 ? dec_.DecodeBits(bits) : 0;
    if (v >= n) return false;
    *id = static_cast<uint32_t>(v);
    return dec_.ok();
  }

  bool SeedComponent() {
    uint32_t corner[3] = {0, 0, 0};
    for (uint32_t& id : corner) {
      const bool ok = dec_.DecodeBit(&models_.is_new) != 0
                          ? NewVertex(SeedPrediction(head_.coding.grid, quanta_), &models_.seed, &id)
                          : GlobalIndex(&id);
      if (!ok) return false;
    }
    return AddFace(corner[0], corner[1], corner[2]);
  }

  bool ExistingCorner(const CompactGate& g, uint32_t* id) {
    if (dec_.DecodeBit(&models_.in_candidates) == 0) return GlobalIndex(id);
    state_.Candidates(g.a, g.b, &candidates_);
    if (candidates_.empty()) return false;
    uint64_t k = 0;
    if (!DecodeCandidateIndex(&dec_, &models_, layout_, GateContext(state_, g), candidates_.size(), &k)) {
      return false;
    }
    *id = candidates_[static_cast<size_t>(k)];
    return dec_.ok();
  }

  bool GrowComponent() {
    CompactGate g;
    while (dec_.ok() && state_.NextGate(&g)) {
      if (dec_.DecodeBit(&models_.has_face) == 0) continue;
      uint32_t d = 0;
      const CompactGrid& grid = head_.coding.grid;
      const bool ok = dec_.DecodeBit(GateIsNewModel(&models_, layout_, state_, g)) != 0
                          ? NewVertex(ParallelogramPrediction(grid, quanta_[g.a], quanta_[g.b], quanta_[g.c]),
                                      &models_.predicted, &d)
                          : ExistingCorner(g, &d);
      if (!ok || !AddFace(g.b, g.a, d)) return false;
    }
    return dec_.ok();
  }

  bool AddFace(uint32_t a, uint32_t b, uint32_t c) {
    return state_.faces().size() < head_.faces && state_.AddFace(a, b, c);
  }

  const ChunkHead& head_;
  const CompactLayout layout_;
  RangeDecoder dec_;
  CompactBaseState state_;
  CompactModels models_;
  std::vector<std::array<int32_t, 3>> quanta_;  // grid indices (interleaved); placeholders otherwise
  std::vector<Vec3> positions_;                  // positions-after layout
  std::vector<uint32_t> candidates_;
};

}  // namespace

StatusOr<Mesh> DecodeCompactBase(const uint8_t* data, size_t size, uint32_t max_vertices,
                                 const std::string& what, CompactLayout layout) {
  ByteReader r(data, size, what);
  ChunkHead head;
  EQMESH_RETURN_IF_ERROR(ReadChunkHead(&r, max_vertices, layout, &head));
  const uint8_t* payload = nullptr;
  const size_t payload_size = r.remaining();
  if (head.vertices > kCompactMaxVerticesPerByte * payload_size + kCompactFaceSlack) {
    return ResourceLimit(what + ": " + std::to_string(head.vertices) + " vertices claimed by " +
                         std::to_string(payload_size) + " payload bytes");
  }
  EQMESH_RETURN_IF_ERROR(r.ReadSpan(payload_size, &payload));
  ChunkReader reader(head, payload, payload_size, layout);
  if (!reader.Run()) {
    return CorruptStream(what + ": connectivity or positions corrupt or truncated (" +
                         std::to_string(head.vertices) + " vertices, " + std::to_string(head.faces) +
                         " faces promised)");
  }
  return reader.TakeMesh();
}

}  // namespace eqmesh

// Compact base-mesh chunk encoder: see compact_base_encoder.h and compact_base_model.h.
// It drives the same CompactBaseState as the decoder, choosing what the decoder
// reads: the seed face of each component (the lowest-numbered face not yet coded)
// and, per gate, the input face across it.
#include "coding/compact_base/compact_base_encoder.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "coding/compact_base/compact_base_model.h"
#include "coding/compact_base/compact_positions.h"
#include "coding/entropy/byte_io.h"

namespace eqmesh {
namespace {

constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();

Status NotCompact(const std::string& why) { return UnsupportedFeature("compact base chunk: " + why); }

// The grid over the mesh's bounding box: origin at its low corner, 2^depth - 1
// steps across the largest extent, indices of ceil(depth) bits.
// (Unreferenced vertices do not count; a mesh with one is refused after the traversal.)
StatusOr<CompactGrid> MakeGrid(const Mesh& mesh, double depth) {
  const BoundingBox box = ComputeBoundingBox(mesh);
  CompactGrid grid;
  grid.bits = static_cast<int>(std::ceil(depth));
  for (int k = 0; k < 3; ++k) grid.origin[static_cast<size_t>(k)] = static_cast<float>(box.min[k]);
  const double extent = (box.max - box.min).maxCoeff();
  // The float step may round below extent / (2^depth - 1): an index can then reach
  // past 2^depth - 1, never past MaxIndex, which Quantize clamps to anyway.
  grid.step = extent > 0 ? static_cast<float>(extent / (std::exp2(depth) - 1.0)) : 1.0f;
  if (!std::isfinite(grid.step) || !(grid.step >= FLT_MIN) ||
      !std::isfinite(grid.origin[0] + grid.origin[1] + grid.origin[2])) {
    return NotCompact("float32 cannot hold the grid");
  }
  return grid;
}

// Codes the connectivity once; in the positions-after layout any number of
// position codings (grid, tangential step) can then follow it (Finish), each
// continuing a copy of the range coder.
class ChunkWriter {
 public:
  // `grid` is used by the interleaved layout only, whose traversal codes positions.
  ChunkWriter(const Mesh& mesh, CompactLayout layout, const CompactGrid& grid)
      : mesh_(mesh), layout_(layout), grid_(grid), state_(static_cast<uint32_t>(mesh.positions.size())),
        coded_face_(mesh.faces.size(), false), decoded_id_(mesh.positions.size(), kUnset) {}

  Status Run() {
    EQMESH_RETURN_IF_ERROR(BuildEdgeFaces());
    size_t next_seed = 0;
    for (;;) {
      while (next_seed < mesh_.faces.size() && coded_face_[next_seed]) ++next_seed;
      enc_.EncodeBit(&models_.more_components, next_seed < mesh_.faces.size());
      if (next_seed == mesh_.faces.size()) break;
      EQMESH_RETURN_IF_ERROR(SeedComponent(next_seed));
      EQMESH_RETURN_IF_ERROR(GrowComponent());
    }
    if (order_.size() != mesh_.positions.size()) return NotCompact("a vertex lies on no face");
    if (layout_ == CompactLayout::kPositionsAfter) {
      ordered_.resize(order_.size());
      for (size_t i = 0; i < order_.size(); ++i) ordered_[i] = mesh_.positions[order_[i]];
    }
    return Status::Ok();
  }

  size_t ConnectivityBytes() const {
    RangeEncoder enc = enc_;
    return enc.Finish().size();
  }

  // The chunk with positions on `coding` (the interleaved layout: grid_ as coded).
  StatusOr<CompactBaseEncoding> Finish(const CompactPositionCoding& coding) const {
    CompactBaseEncoding out;
    RangeEncoder enc = enc_;
    if (layout_ == CompactLayout::kPositionsAfter) {
      out.decoded.positions = EncodeCompactPositions(&enc, coding, state_.faces(), ordered_);
    } else {
      for (const auto& q : quanta_) out.decoded.positions.push_back(grid_.Position(q));
    }
    ByteWriter w;
    w.PutVarint(mesh_.positions.size());
    w.PutVarint(mesh_.faces.size());
    w.PutU8(static_cast<uint8_t>(coding.grid.bits));
    for (const float o : coding.grid.origin) w.PutF32(o);
    w.PutF32(coding.grid.step);
    if (layout_ == CompactLayout::kPositionsAfter) {
      w.PutU8(coding.parallelogram_choice ? kGridChoiceModeByte : static_cast<uint8_t>(coding.tangential_quarters));
    }
    const std::vector<uint8_t> payload = enc.Finish();
    if (mesh_.positions.size() > kCompactMaxVerticesPerByte * payload.size() + kCompactFaceSlack) {
      return NotCompact("more vertices per byte than a decoder accepts");
    }
    w.PutBytes(payload);
    out.bytes = w.Take();
    out.decoded.faces = state_.faces();
    out.decoded_to_input = order_;
    return out;
  }

 private:
  Status BuildEdgeFaces() {
    for (uint32_t f = 0; f < mesh_.faces.size(); ++f) {
      const Face& t = mesh_.faces[f];
      for (int k = 0; k < 3; ++k) {
        std::vector<uint32_t>& faces = edge_faces_[CompactEdgeKey(t[k], t[(k + 1) % 3])];
        faces.push_back(f);
        if (faces.size() > 2) return NotCompact("non-manifold edge");
      }
    }
    return Status::Ok();
  }

  void CodeNewVertex(uint32_t input, const std::array<int32_t, 3>& prediction, CompactResidualModels* models,
                     AdaptiveBit* is_new) {
    enc_.EncodeBit(is_new, 1);
    if (Interleaved()) {
      const std::array<int32_t, 3> q = QuantizeToGrid(grid_, mesh_.positions[input]);
      for (size_t k = 0; k < 3; ++k) EncodeResidual(&enc_, models, int64_t{q[k]} - prediction[k]);
      quanta_.push_back(q);
    }
    decoded_id_[input] = static_cast<uint32_t>(order_.size());
    order_.push_back(input);
  }

  bool Interleaved() const { return layout_ == CompactLayout::kInterleaved; }
  // The interleaved layout's prediction of a new vertex (none in the other layout).
  std::array<int32_t, 3> SeedGuess() const {
    return Interleaved() ? SeedPrediction(grid_, quanta_) : std::array<int32_t, 3>{};
  }
  std::array<int32_t, 3> GateGuess(const CompactGate& g) const {
    return Interleaved() ? ParallelogramPrediction(grid_, quanta_[g.a], quanta_[g.b], quanta_[g.c])
                         : std::array<int32_t, 3>{};
  }

  void CodeGlobalIndex(uint32_t id) {
    const int bits = IndexBits(order_.size());
    if (bits > 0) enc_.EncodeBits(id, bits);
  }

  Status SeedComponent(size_t f) {
    uint32_t corner[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh_.faces[f][k];
      if (decoded_id_[v] == kUnset) {
        CodeNewVertex(v, SeedGuess(), &models_.seed, &models_.is_new);
      } else {
        enc_.EncodeBit(&models_.is_new, 0);
        CodeGlobalIndex(decoded_id_[v]);
      }
      corner[k] = decoded_id_[v];
    }
    return AddFace(f, corner[0], corner[1], corner[2]);
  }

  // The uncoded input face across gate a->b (decoded ids), or kUnset.
  StatusOr<uint32_t> FaceAcross(const CompactGate& g) const {
    const uint32_t a = order_[g.a], b = order_[g.b];
    const auto it = edge_faces_.find(CompactEdgeKey(a, b));
    if (it == edge_faces_.end()) return kUnset;
    for (const uint32_t f : it->second) {
      if (coded_face_[f]) continue;
      const Face& t = mesh_.faces[f];
      for (int k = 0; k < 3; ++k) {
        if (t[k] == b && t[(k + 1) % 3] == a) return f;
      }
      return NotCompact("inconsistent face orientation");
    }
    return kUnset;
  }

  void CodeExistingCorner(const CompactGate& g, uint32_t d) {
    enc_.EncodeBit(GateIsNewModel(&models_, layout_, state_, g), 0);
    state_.Candidates(g.a, g.b, &candidates_);
    const auto it = std::find(candidates_.begin(), candidates_.end(), d);
    enc_.EncodeBit(&models_.in_candidates, it != candidates_.end());
    if (it == candidates_.end()) {
      CodeGlobalIndex(d);
      return;
    }
    EncodeCandidateIndex(&enc_, &models_, layout_, GateContext(state_, g),
                         static_cast<uint64_t>(it - candidates_.begin()), candidates_.size());
  }

  Status GrowComponent() {
    CompactGate g;
    while (state_.NextGate(&g)) {
      EQMESH_ASSIGN_OR_RETURN(const uint32_t f, FaceAcross(g));
      enc_.EncodeBit(&models_.has_face, f != kUnset);
      if (f == kUnset) continue;
      const Face& t = mesh_.faces[f];
      const uint32_t third = t[0] != order_[g.a] && t[0] != order_[g.b] ? t[0]
                             : t[1] != order_[g.a] && t[1] != order_[g.b] ? t[1] : t[2];
      if (decoded_id_[third] == kUnset) {
        CodeNewVertex(third, GateGuess(g), &models_.predicted, GateIsNewModel(&models_, layout_, state_, g));
      } else {
        CodeExistingCorner(g, decoded_id_[third]);
      }
      EQMESH_RETURN_IF_ERROR(AddFace(f, g.b, g.a, decoded_id_[third]));
    }
    return Status::Ok();
  }

  Status AddFace(size_t f, uint32_t a, uint32_t b, uint32_t c) {
    if (!state_.AddFace(a, b, c)) return NotCompact("degenerate face or non-manifold edge");
    coded_face_[f] = true;
    return Status::Ok();
  }

  const Mesh& mesh_;
  const CompactLayout layout_;
  const CompactGrid grid_;
  RangeEncoder enc_;
  CompactBaseState state_;
  CompactModels models_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> edge_faces_;  // looked up only
  std::vector<bool> coded_face_;
  std::vector<uint32_t> decoded_id_;  // input vertex -> decoded id
  std::vector<uint32_t> order_;       // decoded id -> input vertex
  std::vector<std::array<int32_t, 3>> quanta_;  // interleaved: grid indices, decoded order
  std::vector<Vec3> ordered_;                    // positions-after: input positions, decoded order
  std::vector<uint32_t> candidates_;
};

Status CheckCompactMesh(const Mesh& mesh) {
  if (mesh.positions.size() < 3 || mesh.faces.empty()) return NotCompact("needs a face");
  if (mesh.faces.size() > kCompactMaxFacesPerVertex * mesh.positions.size() + kCompactFaceSlack) {
    return NotCompact("more faces than the chunk allows per vertex");
  }
  return Status::Ok();
}

StatusOr<CompactPositionCoding> MakeCoding(const Mesh& mesh, const CompactVariant& v, CompactLayout layout) {
  if (!(v.depth >= 1 && v.depth <= kCompactMaxBits)) return InvalidArgument("compact base chunk: depth out of range");
  if (v.tangential_quarters < kGridTangentialQuarters || v.tangential_quarters > kCompactMaxTangentialQuarters ||
      (layout == CompactLayout::kInterleaved && v.tangential_quarters != kGridTangentialQuarters)) {
    return InvalidArgument("compact base chunk: tangential step out of range");
  }
  if (v.parallelogram_choice && (layout != CompactLayout::kPositionsAfter ||
                                 v.tangential_quarters != kGridTangentialQuarters)) {
    return InvalidArgument("compact base chunk: the parallelogram choice needs the positions-after axis grid");
  }
  CompactPositionCoding coding;
  EQMESH_ASSIGN_OR_RETURN(coding.grid, MakeGrid(mesh, v.depth));
  coding.tangential_quarters = v.tangential_quarters;
  coding.parallelogram_choice = v.parallelogram_choice;
  return coding;
}

}  // namespace

StatusOr<CompactBaseEncoding> EncodeCompactBase(const Mesh& mesh, double depth, CompactLayout layout,
                                               int tangential_quarters) {
  EQMESH_RETURN_IF_ERROR(CheckCompactMesh(mesh));
  EQMESH_ASSIGN_OR_RETURN(const CompactPositionCoding coding,
                          MakeCoding(mesh, {depth, tangential_quarters}, layout));
  ChunkWriter writer(mesh, layout, coding.grid);
  EQMESH_RETURN_IF_ERROR(writer.Run());
  return writer.Finish(coding);
}

StatusOr<size_t> CompactConnectivityBytes(const Mesh& mesh) {
  EQMESH_RETURN_IF_ERROR(CheckCompactMesh(mesh));
  ChunkWriter writer(mesh, CompactLayout::kPositionsAfter, CompactGrid());
  EQMESH_RETURN_IF_ERROR(writer.Run());
  return writer.ConnectivityBytes();
}

StatusOr<std::vector<CompactBaseEncoding>> EncodeCompactBaseVariants(const Mesh& mesh,
                                                                     const std::vector<CompactVariant>& variants) {
  EQMESH_RETURN_IF_ERROR(CheckCompactMesh(mesh));
  std::vector<CompactPositionCoding> codings;
  for (const CompactVariant& v : variants) {
    EQMESH_ASSIGN_OR_RETURN(CompactPositionCoding coding, MakeCoding(mesh, v, CompactLayout::kPositionsAfter));
    codings.push_back(coding);
  }
  ChunkWriter writer(mesh, CompactLayout::kPositionsAfter, CompactGrid());
  EQMESH_RETURN_IF_ERROR(writer.Run());
  std::vector<CompactBaseEncoding> out;
  for (const CompactPositionCoding& coding : codings) {
    EQMESH_ASSIGN_OR_RETURN(CompactBaseEncoding enc, writer.Finish(coding));
    out.push_back(std::move(enc));
  }
  return out;
}

}  // namespace eqmesh

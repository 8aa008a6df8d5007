// Crease chunk: tagged base edges, one adaptive bit each (crease_chunk.h).
#include "coding/crease_chunk.h"

#include <algorithm>
#include <array>

#include "coding/entropy/range_coder.h"

namespace eqmesh {
namespace {

// The base's edges in the order of the level-0 odd vertices.
std::vector<Edge> BaseEdgesInOrder(const SemiRegularHierarchy& hierarchy) {
  if (hierarchy.levels() > 0) return hierarchy.OddEdges(0);
  std::vector<Face> fine;
  std::vector<Edge> edges;
  SubdivideConnectivity(hierarchy.NumVertices(0), hierarchy.BaseFaces(), &fine, &edges);
  return edges;
}

// Context of an edge: tagged edges already coded at its two ends, capped at 2.
class TagContext {
 public:
  explicit TagContext(uint32_t num_vertices) : tagged_at_(num_vertices, 0) {}
  AdaptiveBit* Model(const Edge& e) {
    const uint32_t n = std::min<uint32_t>(2, static_cast<uint32_t>(tagged_at_[e[0]]) + tagged_at_[e[1]]);
    return &models_[n];
  }
  void Tagged(const Edge& e) {
    for (const uint32_t v : e) tagged_at_[v] = static_cast<uint8_t>(std::min(2, tagged_at_[v] + 1));
  }

 private:
  std::vector<uint8_t> tagged_at_;
  std::array<AdaptiveBit, 3> models_;
};

}  // namespace

std::vector<uint8_t> WriteCreaseChunk(const SemiRegularHierarchy& hierarchy) {
  RangeEncoder encoder;
  TagContext context(hierarchy.NumVertices(0));
  for (const Edge& e : BaseEdgesInOrder(hierarchy)) {
    const bool tagged = hierarchy.IsBaseCrease(e);
    encoder.EncodeBit(context.Model(e), tagged ? 1 : 0);
    if (tagged) context.Tagged(e);
  }
  return encoder.Finish();
}

StatusOr<std::vector<Edge>> ReadCreaseChunk(const uint8_t* data, size_t size, const SemiRegularHierarchy& hierarchy) {
  RangeDecoder decoder(data, size);
  TagContext context(hierarchy.NumVertices(0));
  std::vector<Edge> tags;
  for (const Edge& e : BaseEdgesInOrder(hierarchy)) {
    if (decoder.DecodeBit(context.Model(e)) == 0) continue;
    tags.push_back(e);
    context.Tagged(e);
  }
  if (!decoder.ok()) return CorruptStream("eqm crease chunk: truncated");
  EQMESH_RETURN_IF_ERROR(decoder.CheckConsumedAll("eqm crease chunk"));
  if (tags.empty()) return CorruptStream("eqm crease chunk: no edge is tagged");
  return tags;
}

}  // namespace eqmesh

// Half-edge adjacency for butterfly stencils. Plain mesh data-structure code; no
// paper beyond the usual half-edge conventions (Mäntylä 1988, Kettner 1999).
#include "wavelet/level_adjacency.h"

namespace eqmesh {

LevelAdjacency::LevelAdjacency(uint32_t num_vertices, const std::vector<Face>& faces)
    : faces_(&faces) {
  BucketOutgoing(num_vertices);
  PairTwins();
  ClassifyVertices();
}

void LevelAdjacency::BucketOutgoing(uint32_t num_vertices) {
  const uint32_t num_half = static_cast<uint32_t>(faces_->size() * 3);
  out_offsets_.assign(static_cast<size_t>(num_vertices) + 1, 0);
  for (uint32_t h = 0; h < num_half; ++h) ++out_offsets_[From(h) + 1];
  for (uint32_t v = 0; v < num_vertices; ++v) out_offsets_[v + 1] += out_offsets_[v];
  // Filling in increasing h keeps each bucket sorted, so the result is unique.
  std::vector<uint32_t> cursor(out_offsets_.begin(), out_offsets_.end() - 1);
  out_half_.resize(num_half);
  out_to_.resize(num_half);
  for (uint32_t h = 0; h < num_half; ++h) {
    const uint32_t slot = cursor[From(h)]++;
    out_half_[slot] = h;
    out_to_[slot] = To(h);
  }
}

uint32_t LevelAdjacency::FindSlot(uint32_t a, uint32_t b) const {
  if (a + 1 >= out_offsets_.size()) return kNone;
  uint32_t found = kNone;
  for (uint32_t i = out_offsets_[a]; i < out_offsets_[a + 1]; ++i) {
    if (out_to_[i] != b) continue;
    if (found != kNone) return kNone;  // a -> b used twice: not manifold
    found = i;
  }
  return found;
}

uint32_t LevelAdjacency::FindHalfEdge(uint32_t a, uint32_t b) const {
  const uint32_t slot = FindSlot(a, b);
  return slot == kNone ? kNone : out_half_[slot];
}

void LevelAdjacency::PairTwins() {
  const uint32_t num_vertices = static_cast<uint32_t>(out_offsets_.size() - 1);
  twin_.assign(out_half_.size(), kNone);
  edge_type_.assign(out_half_.size(), EdgeType::kNonManifold);
  for (uint32_t a = 0; a < num_vertices; ++a) {
    for (uint32_t i = out_offsets_[a]; i < out_offsets_[a + 1]; ++i) {
      const uint32_t b = out_to_[i];
      if (FindSlot(a, b) != i) continue;  // duplicated direction
      uint32_t reverse_count = 0, reverse = kNone;
      for (uint32_t r = out_offsets_[b]; r < out_offsets_[b + 1]; ++r) {
        if (out_to_[r] == a) {
          ++reverse_count;
          reverse = out_half_[r];
        }
      }
      const uint32_t h = out_half_[i];
      if (reverse_count == 0) {
        edge_type_[h] = EdgeType::kBoundary;
      } else if (reverse_count == 1) {
        edge_type_[h] = EdgeType::kInterior;
        twin_[h] = reverse;
      }
    }
  }
}

void LevelAdjacency::ClassifyVertices() {
  const uint32_t num_vertices = static_cast<uint32_t>(out_offsets_.size() - 1);
  vertex_type_.assign(num_vertices, VertexType::kIsolated);
  ring_.assign(out_half_.size(), kNone);
  boundary_next_.assign(num_vertices, kNone);
  boundary_prev_.assign(num_vertices, kNone);
  for (uint32_t v = 0; v < num_vertices; ++v) vertex_type_[v] = ClassifyVertex(v);
}

// Walks the fan of v by h -> Twin(Prev(h)) (counter-clockwise for CCW faces). v is
// interior when one closed walk visits every outgoing half-edge, boundary when it
// has exactly one boundary edge in and one out and the open walk between them
// visits every outgoing half-edge; anything else (several fans, non-manifold
// edges) is non-manifold.
LevelAdjacency::VertexType LevelAdjacency::ClassifyVertex(uint32_t v) {
  const uint32_t begin = out_offsets_[v], degree = Valence(v);
  if (degree == 0) return VertexType::kIsolated;
  uint32_t boundary_out = kNone, boundary_out_count = 0, boundary_in_count = 0;
  for (uint32_t i = begin; i < begin + degree; ++i) {
    const uint32_t h = out_half_[i];
    const uint32_t in = Prev(h);  // the incoming half-edge of the same face
    if (edge_type_[h] == EdgeType::kNonManifold || edge_type_[in] == EdgeType::kNonManifold)
      return VertexType::kNonManifold;
    if (edge_type_[h] == EdgeType::kBoundary) {
      ++boundary_out_count;
      boundary_out = h;
    }
    if (edge_type_[in] == EdgeType::kBoundary) {
      ++boundary_in_count;
      boundary_prev_[v] = From(in);
    }
  }
  const bool closed = boundary_out_count == 0 && boundary_in_count == 0;
  if (!closed && (boundary_out_count != 1 || boundary_in_count != 1))
    return VertexType::kNonManifold;
  const uint32_t start = closed ? out_half_[begin] : boundary_out;
  uint32_t h = start;
  for (uint32_t i = 0; i < degree; ++i) {
    ring_[begin + i] = To(h);
    const uint32_t next = Twin(Prev(h));
    const bool last = i + 1 == degree;
    if (next == kNone) {  // reached the incoming boundary edge
      if (closed || !last) return VertexType::kNonManifold;
      boundary_next_[v] = To(boundary_out);
      return VertexType::kBoundary;
    }
    if ((next == start) != (closed && last)) return VertexType::kNonManifold;
    h = next;
  }
  return closed ? VertexType::kInterior : VertexType::kNonManifold;
}

}  // namespace eqmesh

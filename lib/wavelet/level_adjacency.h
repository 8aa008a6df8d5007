// Half-edge adjacency of one level of a semi-regular hierarchy, built from the
// face list alone so encoder and decoder derive identical stencils. Standard
// half-edge conventions (Mäntylä 1988; Kettner 1999), no paper-specific algorithm.
//
// Half-edge h = 3*f + i runs from faces[f][i] to faces[f][(i+1)%3]; no extra
// storage is needed for from/to/apex. Outgoing half-edges are bucketed per vertex
// (CSR, counting sort: O(F), no hashing), and twins are found by scanning the
// short outgoing list of the target vertex.
//
// Anything that is not a 2-manifold (an edge used twice in the same direction or
// by more than two faces, a vertex with several fans) is classified rather than
// rejected: the butterfly code falls back to simpler stencils there.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh {

class LevelAdjacency {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFFu;

  enum class EdgeType : uint8_t { kInterior, kBoundary, kNonManifold };
  enum class VertexType : uint8_t { kIsolated, kInterior, kBoundary, kNonManifold };

  // `faces` must outlive the adjacency; indices must be < num_vertices.
  LevelAdjacency(uint32_t num_vertices, const std::vector<Face>& faces);

  uint32_t From(uint32_t h) const { return (*faces_)[h / 3][h % 3]; }
  uint32_t To(uint32_t h) const { return (*faces_)[h / 3][(h % 3 + 1) % 3]; }
  // Vertex of h's face opposite h.
  uint32_t Apex(uint32_t h) const { return (*faces_)[h / 3][(h % 3 + 2) % 3]; }
  static uint32_t Next(uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
  static uint32_t Prev(uint32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
  static uint32_t FaceOf(uint32_t h) { return h / 3; }

  // Reverse half-edge, kNone unless the edge is interior (exactly one each way).
  uint32_t Twin(uint32_t h) const { return twin_[h]; }
  EdgeType TypeOfEdge(uint32_t h) const { return edge_type_[h]; }
  // The unique half-edge a -> b, kNone if absent or duplicated.
  uint32_t FindHalfEdge(uint32_t a, uint32_t b) const;

  VertexType TypeOfVertex(uint32_t v) const { return vertex_type_[v]; }
  // Interior vertices: number of neighbours (= incident faces).
  uint32_t Valence(uint32_t v) const { return out_offsets_[v + 1] - out_offsets_[v]; }
  // Interior vertices: neighbours in counter-clockwise order, Valence(v) entries.
  const uint32_t* Ring(uint32_t v) const { return ring_.data() + out_offsets_[v]; }
  // Boundary vertices: neighbour after / before v along its boundary loop, which
  // runs in the direction of the boundary half-edges (interior on the left).
  uint32_t BoundaryNext(uint32_t v) const { return boundary_next_[v]; }
  uint32_t BoundaryPrev(uint32_t v) const { return boundary_prev_[v]; }

 private:
  void BucketOutgoing(uint32_t num_vertices);
  void PairTwins();
  // Position in out_half_ of the unique half-edge a -> b, kNone if absent or duplicated.
  uint32_t FindSlot(uint32_t a, uint32_t b) const;
  void ClassifyVertices();
  VertexType ClassifyVertex(uint32_t v);

  const std::vector<Face>* faces_;
  std::vector<uint32_t> out_offsets_;  // CSR over vertices
  std::vector<uint32_t> out_half_;     // outgoing half-edges per vertex
  std::vector<uint32_t> out_to_;       // To(out_half_[i]), contiguous for fast scans
  std::vector<uint32_t> twin_;
  std::vector<EdgeType> edge_type_;
  std::vector<VertexType> vertex_type_;
  std::vector<uint32_t> ring_;  // same CSR offsets as out_half_
  std::vector<uint32_t> boundary_next_;
  std::vector<uint32_t> boundary_prev_;
};

}  // namespace eqmesh

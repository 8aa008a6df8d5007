// Reusable adjacency of an indexed triangle mesh, built once and queried by the
// diagnosis, the repair and the remesher.
//
// Follows the usual "indexed face set + sorted edge list" construction (as in
// libigl's edge_topology / OpenMesh import): every face corner i of face f is a
// half-edge h = 3f + i running from face[f][i] to face[f][(i+1)%3]; half-edges are
// bucketed by their smaller endpoint (counting sort, O(n)) and sorted by the
// larger one inside each bucket, so undirected edges come out ordered by
// (min, max) without a per-edge map. No half-edge structure is imposed: edges may
// carry any number of faces, which is what diagnosis needs to see.
//
// Faces with an out-of-range or repeated index have no meaningful edges; they are
// marked unusable and take part in nothing below (no edges, stars, components).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"  // Edge

namespace eqmesh {

// A read-only view of consecutive uint32_t values (C++17 has no std::span).
struct IndexRange {
  const uint32_t* first = nullptr;
  const uint32_t* last = nullptr;
  const uint32_t* begin() const { return first; }
  const uint32_t* end() const { return last; }
  size_t size() const { return static_cast<size_t>(last - first); }
  bool empty() const { return first == last; }
  uint32_t operator[](size_t i) const { return first[i]; }
};

// An ordered boundary cycle: vertices[k] -> vertices[k+1] is edge edges[k]; the
// last vertex connects back to the first. `closed` is false only when the walk
// could not return to its start (possible at non-manifold edges).
struct BoundaryLoop {
  std::vector<uint32_t> vertices;
  std::vector<uint32_t> edges;
  uint32_t component = 0;
  bool closed = true;
};

// Result of propagating one face's orientation over its component.
struct OrientationPlan {
  std::vector<uint8_t> flip;             // per face: 1 = reverse it to agree with its component
  std::vector<uint32_t> conflict_edges;  // two-face edges no choice of flips can make consistent
  size_t faces_to_flip = 0;
};

// Splits faces that all contain `center` into fans: two faces are joined when
// they share an edge (center, x) that neither of them has cut. `cut_masks` is
// empty or holds one byte per face of `star` (bit i set = edge (f[i], f[i+1])
// joins nothing). Writes a label in [0, count) per face, numbered by first
// appearance, and returns count.
uint32_t LabelFans(uint32_t center, const std::vector<Face>& star, const std::vector<uint8_t>& cut_masks,
                   std::vector<uint32_t>* labels);

class MeshTopology {
 public:
  static constexpr uint32_t kNone = 0xffffffffu;

  MeshTopology() = default;
  // Copies the faces, so `mesh` need not outlive the topology.
  explicit MeshTopology(const Mesh& mesh);

  size_t num_vertices() const { return num_vertices_; }
  size_t num_faces() const { return faces_.size(); }
  size_t num_edges() const { return edges_.size(); }
  const std::vector<Face>& faces() const { return faces_; }

  // False for faces with an index >= num_vertices or a repeated index.
  bool FaceUsable(uint32_t f) const { return usable_[f] != 0; }
  size_t num_unusable_faces() const { return num_unusable_; }

  // --- Half-edges: h = 3f + i, from faces[f][i] to faces[f][(i+1)%3].
  static uint32_t HalfedgeFace(uint32_t h) { return h / 3; }
  uint32_t HalfedgeFrom(uint32_t h) const { return faces_[h / 3][h % 3]; }
  uint32_t HalfedgeTo(uint32_t h) const { return faces_[h / 3][(h % 3 + 1) % 3]; }
  // Undirected edge of a half-edge; kNone for half-edges of unusable faces.
  uint32_t HalfedgeEdge(uint32_t h) const { return halfedge_edge_[h]; }

  // --- Undirected edges, ordered by (min, max) vertex.
  const Edge& EdgeVertices(uint32_t e) const { return edges_[e]; }  // [0] < [1]
  // Half-edges on edge e, in increasing order (so faces in increasing order).
  IndexRange EdgeHalfedges(uint32_t e) const { return Range(edge_halfedges_, edge_offsets_, e); }
  uint32_t EdgeFaceCount(uint32_t e) const { return edge_offsets_[e + 1] - edge_offsets_[e]; }
  bool IsBoundaryEdge(uint32_t e) const { return EdgeFaceCount(e) == 1; }
  bool IsNonManifoldEdge(uint32_t e) const { return EdgeFaceCount(e) > 2; }
  // A two-face edge whose faces traverse it in the same direction. Edges with
  // more than two faces are reported as non-manifold instead, never here.
  bool IsInconsistentEdge(uint32_t e) const;
  // Edge between a and b, or kNone (binary search in a's bucket).
  uint32_t FindEdge(uint32_t a, uint32_t b) const;

  // --- Vertex stars.
  // Usable faces containing v, in increasing order.
  IndexRange VertexFaces(uint32_t v) const { return Range(vertex_faces_, vertex_offsets_, v); }
  bool IsReferenced(uint32_t v) const { return vertex_offsets_[v + 1] > vertex_offsets_[v]; }

  // Splits the star of v into fans: faces are joined when they share an edge
  // (v, x). Writes one label in [0, count) per face of VertexFaces(v) (labels
  // numbered by first appearance, so the fan holding the lowest face is 0) and
  // returns the count: 0 for an unreferenced vertex, 1 for a manifold one, more
  // for a "pinched" vertex. With `cut_mask` (one byte per face, bit i set = edge
  // (f[i], f[i+1]) of that face joins nothing), cut edges do not join faces.
  uint32_t VertexFans(uint32_t v, std::vector<uint32_t>* labels,
                      const std::vector<uint8_t>* cut_mask = nullptr) const;

  // --- Face-connected components (faces joined through shared edges).
  size_t num_components() const { return num_components_; }
  // Component of each face (numbered by lowest face); kNone for unusable faces.
  const std::vector<uint32_t>& FaceComponents() const { return face_component_; }
  uint32_t EdgeComponent(uint32_t e) const { return face_component_[HalfedgeFace(EdgeHalfedges(e)[0])]; }

  // --- Orientation.
  // Breadth-first propagation from the lowest face of each component across
  // two-face edges (non-manifold edges are not crossed). A component is
  // orientable exactly when none of its edges ends up in conflict_edges.
  OrientationPlan PlanConsistentOrientation() const;

  // --- Boundary (edges with exactly one face).
  // Every boundary edge lies on exactly one loop. Loops follow the orientation of
  // their faces and, at a vertex touching several loops, turn within the fan of
  // the face they arrived on, so a pinched boundary yields separate loops.
  std::vector<BoundaryLoop> BoundaryLoops() const;

 private:
  static IndexRange Range(const std::vector<uint32_t>& items, const std::vector<uint32_t>& offsets,
                          uint32_t i) {
    return {items.data() + offsets[i], items.data() + offsets[i + 1]};
  }
  void MarkUsableFaces();
  void BuildEdges();
  void BuildVertexStars();
  void BuildComponents();
  uint32_t FanWalkToBoundary(uint32_t from_edge, uint32_t from_face, uint32_t at_vertex) const;
  uint32_t AnyUnusedBoundaryEdge(uint32_t v, uint32_t component, const std::vector<uint8_t>& used) const;

  size_t num_vertices_ = 0;
  size_t num_unusable_ = 0;
  size_t num_components_ = 0;
  std::vector<Face> faces_;
  std::vector<uint8_t> usable_;
  std::vector<Edge> edges_;
  std::vector<uint32_t> edge_offsets_{0};
  std::vector<uint32_t> edge_halfedges_;
  std::vector<uint32_t> halfedge_edge_;
  std::vector<uint32_t> vertex_offsets_{0};
  std::vector<uint32_t> vertex_faces_;
  std::vector<uint32_t> face_component_;
};

}  // namespace eqmesh

// Semi-regular connectivity: a base mesh refined J times by 1-to-4 subdivision.
//
// The connectivity of every level is a pure function of the base faces, so the
// codec sends only the base mesh and the decoder rebuilds the rest. The rules
// below are normative (ext_spec/ Appendix B restates them) and must never change
// without a bitstream version bump:
//
//  * Vertices are nested: level j has vertices [0, NumVertices(j)); level j+1
//    appends one "odd" vertex per edge of level j.
//  * Odd vertex numbering: walk the faces of level j in order; for face
//    (v0, v1, v2) visit its edges (v0,v1), (v1,v2), (v2,v0); an undirected edge
//    seen for the first time gets the next odd index. OddEdge(j, k) stores the
//    edge as first visited (the orientation of the first face using it).
//  * Faces: face f = (a, b, c) of level j with odd vertices m_ab, m_bc, m_ca has
//    children 4f+0 = (a, m_ab, m_ca), 4f+1 = (m_ab, b, m_bc),
//    4f+2 = (m_ca, m_bc, c), 4f+3 = (m_ab, m_bc, m_ca). Orientation is kept and
//    the faces of base triangle t at level j are [t*4^j, (t+1)*4^j).
//  * Crease edges: a set of base edges may be tagged (SetBaseCreases); the two
//    halves (a, m) and (m, b) of a tagged level-j edge (a, b) with odd vertex m
//    are tagged at level j+1, and no other edge is. The butterfly predicts
//    along tagged edges as along a boundary (wavelet/butterfly.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

using Edge = std::array<uint32_t, 2>;

class SemiRegularHierarchy {
 public:
  SemiRegularHierarchy() = default;

  // Validates the base (indices < base_vertices, no degenerate face) and builds
  // `levels` refinements. Refuses counts whose finest level would exceed
  // max_finest_faces, so hostile headers cannot force huge allocations.
  static StatusOr<SemiRegularHierarchy> Build(uint32_t base_vertices, std::vector<Face> base_faces,
                                              int levels, uint64_t max_finest_faces = (1ull << 28));

  // Appends one refinement level (same rules, same result as building it at once);
  // on failure (ResourceLimit when the new finest level would exceed
  // max_finest_faces) the hierarchy is unchanged. Lets the decoder allocate a level
  // only once the stream has shown it holds that level's data.
  Status Refine(uint64_t max_finest_faces = (1ull << 28));

  int levels() const { return static_cast<int>(faces_.size()) - 1; }
  uint32_t NumVertices(int level) const { return vertex_counts_[level]; }
  uint32_t NumOddVertices(int j) const { return vertex_counts_[j + 1] - vertex_counts_[j]; }
  const std::vector<Face>& Faces(int level) const { return faces_[level]; }
  const std::vector<Face>& BaseFaces() const { return faces_[0]; }
  // Moves level `level`'s faces out, leaving that level without faces: for a
  // caller done with the hierarchy (ExtractLevel of a temporary mesh).
  std::vector<Face> TakeFaces(int level) { return std::move(faces_[level]); }
  // Edge of level j carrying odd vertex NumVertices(j) + k, for k < NumOddVertices(j).
  const Edge& OddEdge(int j, uint32_t k) const { return odd_edges_[j][k]; }
  const std::vector<Edge>& OddEdges(int j) const { return odd_edges_[j]; }
  // Level at which vertex v first appears (0 for base vertices).
  int VertexLevel(uint32_t v) const;

  // Tags the given base edges (either orientation) as creases, for every level
  // built and to come. InvalidMesh when one is not an edge of a base face.
  Status SetBaseCreases(std::vector<Edge> edges);
  // The tagged base edges, each (smaller, larger), sorted; empty: none.
  const std::vector<Edge>& BaseCreases() const { return base_creases_; }
  bool HasCreases() const { return !base_creases_.empty(); }
  // Whether base edge e (either orientation) is tagged.
  bool IsBaseCrease(const Edge& e) const;
  // Whether odd vertex NumVertices(j) + k refines a tagged level-j edge.
  bool IsCreaseOdd(int j, uint32_t k) const { return !crease_odd_[j].empty() && crease_odd_[j][k] != 0; }

  // Face and odd-edge counts a hierarchy would have, without building it.
  static uint64_t FinestFaceCount(uint64_t base_faces, int levels);

 private:
  std::vector<uint32_t> vertex_counts_;          // size levels+1
  std::vector<std::vector<Face>> faces_;         // size levels+1
  std::vector<std::vector<Edge>> odd_edges_;     // size levels
  std::vector<Edge> base_creases_;
  std::vector<std::vector<uint8_t>> crease_odd_;  // size levels; per odd vertex, empty without creases

  std::vector<uint8_t> TagCreaseOdds(int j) const;
};

// Kind of each vertex of a remeshed semi-regular mesh.
enum class VertexKind : uint8_t {
  kBase = 0,       // base vertex: an input vertex, coded as a scaling coefficient
  kNormal = 1,     // offset from its butterfly prediction along the predicted normal
  kNonNormal = 2,  // parametric fallback: needs all three wavelet components
  kBoundary = 3,   // on an input boundary curve (not pierced)
};

// The remesher's output and the codec's input.
struct SemiRegularMesh {
  SemiRegularHierarchy hierarchy;
  std::vector<Vec3> positions;      // hierarchy.NumVertices(levels()) entries
  std::vector<VertexKind> kinds;    // same size; empty when unknown (e.g. decoded)
  Mesh kept_exactly;                // components too small to remesh, carried as is
};

// Level `level` of a semi-regular mesh as a plain mesh (kept_exactly appended).
Mesh ExtractLevel(const SemiRegularMesh& mesh, int level);
// Appends `kept` (a SemiRegularMesh's kept_exactly) to `out`, its indices offset by
// out's vertex count: how every extraction of a level ends.
void AppendKeptComponents(const Mesh& kept, Mesh* out);
// The same for a mesh the caller is done with: the finest level's positions and
// faces are moved rather than copied (a decoder's last step).
Mesh ExtractLevel(SemiRegularMesh&& mesh, int level);

// Refines connectivity only: returns the faces of the next level and the odd edges,
// following the rules at the top of this file. Exposed for tests and the remesher.
void SubdivideConnectivity(uint32_t num_vertices, const std::vector<Face>& faces,
                           std::vector<Face>* fine_faces, std::vector<Edge>* odd_edges);

}  // namespace eqmesh

// Crease edges of one level, by half-edge and by vertex (crease_edges.h).
#include "wavelet/crease_edges.h"

namespace eqmesh {

CreaseEdges::CreaseEdges(const SemiRegularHierarchy& hierarchy, int j, const LevelAdjacency& adjacency) {
  if (!hierarchy.HasCreases()) return;
  const uint32_t num_odd = hierarchy.NumOddVertices(j);
  const uint32_t num_vertices = hierarchy.NumVertices(j);
  half_.assign(hierarchy.Faces(j).size() * 3, 0);
  count_.assign(num_vertices, 0);
  neighbours_.assign(num_vertices, {LevelAdjacency::kNone, LevelAdjacency::kNone});
  const auto link = [this](uint32_t v, uint32_t other) {
    if (count_[v] < 2) neighbours_[v][count_[v]] = other;
    if (count_[v] < 3) ++count_[v];
  };
  for (uint32_t k = 0; k < num_odd; ++k) {
    if (!hierarchy.IsCreaseOdd(j, k)) continue;
    const Edge& e = hierarchy.OddEdge(j, k);
    for (const uint32_t h : {adjacency.FindHalfEdge(e[0], e[1]), adjacency.FindHalfEdge(e[1], e[0])}) {
      if (h != LevelAdjacency::kNone) half_[h] = 1;
    }
    link(e[0], e[1]);
    link(e[1], e[0]);
  }
}

}  // namespace eqmesh

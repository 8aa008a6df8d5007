// Crease edges of one level, as sorted lists (crease_edges.h).
#include "wavelet/crease_edges.h"

#include <algorithm>

namespace eqmesh {

CreaseEdges::CreaseEdges(const SemiRegularHierarchy& hierarchy, int j, const LevelAdjacency& adjacency)
    : adjacency_(adjacency) {
  if (!hierarchy.HasCreases()) return;
  count_.assign(hierarchy.NumVertices(j), 0);
  const uint32_t num_odd = hierarchy.NumOddVertices(j);
  for (uint32_t k = 0; k < num_odd; ++k) {
    if (!hierarchy.IsCreaseOdd(j, k)) continue;
    const Edge& e = hierarchy.OddEdge(j, k);
    for (int end = 0; end < 2; ++end) {
      const uint32_t v = e[end], other = e[1 - end];
      links_.emplace_back(v, other);
      if (count_[v] < 3) ++count_[v];
    }
  }
  std::sort(links_.begin(), links_.end());
}

bool CreaseEdges::IsCrease(uint32_t h) const {
  if (count_.empty()) return false;
  const uint32_t a = adjacency_.From(h), b = adjacency_.To(h);
  if (count_[a] == 0 || count_[b] == 0) return false;
  // Each tagged edge is linked from both ends.
  return std::binary_search(links_.begin(), links_.end(), std::make_pair(a, b));
}

uint32_t CreaseEdges::ContinuationPast(uint32_t v, uint32_t from) const {
  const auto first = std::lower_bound(links_.begin(), links_.end(), std::make_pair(v, uint32_t{0}));
  // Count(v) == 2: the two links of v are adjacent in the sorted list.
  return first->second == from ? (first + 1)->second : first->second;
}

}  // namespace eqmesh

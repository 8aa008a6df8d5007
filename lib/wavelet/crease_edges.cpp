// Crease edges of one level, as sorted lists (crease_edges.h).
#include "wavelet/crease_edges.h"

#include <algorithm>

namespace eqmesh {
namespace {

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

CreaseEdges::CreaseEdges(const SemiRegularHierarchy& hierarchy, int j, const LevelAdjacency& adjacency)
    : adjacency_(adjacency) {
  if (!hierarchy.HasCreases()) return;
  count_.assign(hierarchy.NumVertices(j), 0);
  const uint32_t num_odd = hierarchy.NumOddVertices(j);
  for (uint32_t k = 0; k < num_odd; ++k) {
    if (!hierarchy.IsCreaseOdd(j, k)) continue;
    const Edge& e = hierarchy.OddEdge(j, k);
    edges_.push_back(EdgeKey(e[0], e[1]));
    for (int end = 0; end < 2; ++end) {
      const uint32_t v = e[end], other = e[1 - end];
      links_.emplace_back(v, other);
      if (count_[v] < 3) ++count_[v];
    }
  }
  std::sort(edges_.begin(), edges_.end());
  std::sort(links_.begin(), links_.end());
}

bool CreaseEdges::IsCrease(uint32_t h) const {
  if (count_.empty()) return false;
  const uint32_t a = adjacency_.From(h), b = adjacency_.To(h);
  if (count_[a] == 0 || count_[b] == 0) return false;
  return std::binary_search(edges_.begin(), edges_.end(), EdgeKey(a, b));
}

uint32_t CreaseEdges::ContinuationPast(uint32_t v, uint32_t from) const {
  const auto first = std::lower_bound(links_.begin(), links_.end(), std::make_pair(v, uint32_t{0}));
  // Count(v) == 2: the two links of v are adjacent in the sorted list.
  return first->second == from ? (first + 1)->second : first->second;
}

}  // namespace eqmesh

// The tagged crease edges of one level of a semi-regular hierarchy, as the
// butterfly stencils ask for them: by half-edge, and the crease neighbours of
// each vertex. Built from connectivity and the hierarchy's tags only, so
// encoder and decoder derive the same.
//
// Papers: Hoppe et al. 1994 (piecewise smooth subdivision: tagged sharp edges
// refined by the curve rule, vertices with two of them treated as on a
// boundary); Zorin, Schröder, Sweldens 1996 (the butterfly's boundary rules,
// which the crease rules reuse on each side). Departure: no corner or dart
// masks beyond what the boundary rules give (butterfly.cpp, rules C1-C3).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/semi_regular.h"
#include "wavelet/level_adjacency.h"

namespace eqmesh {

class CreaseEdges {
 public:
  // The tagged edges of level j (SemiRegularHierarchy::IsCreaseOdd); j <
  // hierarchy.levels(). Empty when the hierarchy has no creases.
  CreaseEdges(const SemiRegularHierarchy& hierarchy, int j, const LevelAdjacency& adjacency);

  bool empty() const { return half_.empty(); }
  // Whether half-edge h lies on a tagged edge.
  bool IsCrease(uint32_t h) const { return !half_.empty() && half_[h] != 0; }
  // Tagged edges at vertex v (saturating at 3).
  uint32_t Count(uint32_t v) const { return half_.empty() ? 0 : count_[v]; }
  // For a vertex with exactly two tagged edges: the crease neighbour other than `from`.
  uint32_t ContinuationPast(uint32_t v, uint32_t from) const {
    return neighbours_[v][0] == from ? neighbours_[v][1] : neighbours_[v][0];
  }

 private:
  std::vector<uint8_t> half_;  // per half-edge
  std::vector<uint8_t> count_;
  std::vector<std::array<uint32_t, 2>> neighbours_;  // the first two crease neighbours
};

}  // namespace eqmesh

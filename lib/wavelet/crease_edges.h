// The tagged crease edges of one level of a semi-regular hierarchy, as the
// butterfly stencils ask for them: whether a half-edge is tagged, and the
// crease neighbours of a vertex. Built from connectivity and the hierarchy's
// tags only, so encoder and decoder derive the same.
//
// Papers: Hoppe et al. 1994 (piecewise smooth subdivision: tagged sharp edges
// refined by the curve rule, vertices with two of them treated as on a
// boundary); Zorin, Schröder, Sweldens 1996 (the butterfly's boundary rules,
// which the crease rules reuse on each side). Departure: no corner or dart
// masks beyond what the boundary rules give (butterfly.cpp, rules C1-C3).
//
// Tagged edges are sparse (2^j per tagged base edge at level j, the level's
// edges 4^j per base face), so they are kept as a sorted list of links (each
// edge from both ends), with one byte per vertex that answers "no crease here"
// for almost every query.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/semi_regular.h"
#include "wavelet/level_adjacency.h"

namespace eqmesh {

class CreaseEdges {
 public:
  // The tagged edges of level j (SemiRegularHierarchy::IsCreaseOdd); j <
  // hierarchy.levels(). Empty when the hierarchy has no creases. Holds a
  // reference to `adjacency`.
  CreaseEdges(const SemiRegularHierarchy& hierarchy, int j, const LevelAdjacency& adjacency);

  // Whether half-edge h lies on a tagged edge.
  bool IsCrease(uint32_t h) const;
  // Tagged edges at vertex v (saturating at 3).
  uint32_t Count(uint32_t v) const { return count_.empty() ? 0 : count_[v]; }
  // For a vertex with exactly two tagged edges: the crease neighbour other than `from`.
  uint32_t ContinuationPast(uint32_t v, uint32_t from) const;

 private:
  const LevelAdjacency& adjacency_;
  std::vector<uint8_t> count_;                         // per vertex; empty without creases
  std::vector<std::pair<uint32_t, uint32_t>> links_;   // (vertex, crease neighbour), sorted
};

}  // namespace eqmesh

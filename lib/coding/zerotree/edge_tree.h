// Edge quadtree of a semi-regular hierarchy: the parent/child relation the zerotree
// coder runs on (Khodakovsky, Schröder, Sweldens 2000, PGC, "edge tree"; the seed
// paper's Fig. 4, Lavu, Choi, Baraniuk 2003).
//
// Node (j, k) is the odd vertex NumVertices(j) + k of refinement level j, i.e. the
// edge OddEdge(j, k) of level j. Its children are the odd vertices of level j + 1 on
// the two halves of that edge and on the interior edge parallel to it in each split
// adjacent face: 4 on an interior edge of a manifold mesh, 3 on a boundary edge.
// Every odd vertex of level >= 1 has exactly one parent; the level-0 odd vertices
// (the base edges) are the roots.
//
// Normative child order: the children of a node are listed in increasing odd
// index. The relation is derived from the normative face order of
// SemiRegularHierarchy only (face f = (v0, v1, v2) -> 4f..4f+3), so both codec sides
// rebuild it from the base connectivity.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh::zerotree {

constexpr uint32_t kNoParent = 0xFFFFFFFFu;

// Nodes are numbered globally: node = level_offset[j] + k.
struct EdgeTree {
  int levels = 0;
  std::vector<uint32_t> level_offset;  // levels + 1 entries
  std::vector<uint8_t> level;          // per node
  std::vector<uint32_t> parent;        // per node; kNoParent for roots
  std::vector<uint32_t> child_begin;   // CSR: children of n in [child_begin[n], child_begin[n+1])
  std::vector<uint32_t> children;      // global node ids, increasing within a node

  uint32_t num_nodes() const { return level_offset.empty() ? 0 : level_offset.back(); }
  uint32_t num_roots() const { return levels > 0 ? level_offset[1] : 0; }
  uint32_t ChildCount(uint32_t n) const { return child_begin[n + 1] - child_begin[n]; }
};

// Tree over the odd vertices of refinement levels 0..levels-1; needs
// 0 <= levels <= hierarchy.levels().
StatusOr<EdgeTree> BuildEdgeTree(const SemiRegularHierarchy& hierarchy, int levels);

}  // namespace eqmesh::zerotree

// Edge quadtree: see edge_tree.h for the papers followed and the normative order.
#include "coding/zerotree/edge_tree.h"

#include <string>

namespace eqmesh::zerotree {
namespace {

// Coarse face (v0, v1, v2) with midpoints m01, m12, m20 (slots 0, 1, 2) splits into
// c0 = (v0, m01, m20), c1 = (m01, v1, m12), c2 = (m20, m12, v2), c3 = (m01, m12, m20).
// kParentSlot[c][e] is the coarse midpoint slot owning edge e of child c, edges
// taken as (g0, g1), (g1, g2), (g2, g0): halves belong to the edge they halve,
// interior edges to the coarse edge they are parallel to.
constexpr int kParentSlot[4][3] = {{0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {2, 0, 1}};

// Odd vertices (global vertex ids) on the edges (g0,g1), (g1,g2), (g2,g0) of face
// g of `level`, read from the normative children of g at level + 1.
std::array<uint32_t, 3> FaceMidpoints(const SemiRegularHierarchy& h, int level, size_t g) {
  const std::vector<Face>& fine = h.Faces(level + 1);
  return {fine[4 * g][1], fine[4 * g + 1][2], fine[4 * g][2]};
}

// Sets the parent of every node of level j + 1 from the faces of level j.
Status AssignParents(const SemiRegularHierarchy& h, int j, EdgeTree* tree) {
  const uint32_t coarse_base = h.NumVertices(j), fine_base = h.NumVertices(j + 1);
  const uint32_t coarse_odd = h.NumOddVertices(j), fine_odd = h.NumOddVertices(j + 1);
  const size_t faces = h.Faces(j).size();
  for (size_t f = 0; f < faces; ++f) {
    const std::array<uint32_t, 3> mid = FaceMidpoints(h, j, f);
    for (int c = 0; c < 4; ++c) {
      const std::array<uint32_t, 3> fine_mid = FaceMidpoints(h, j + 1, 4 * f + static_cast<size_t>(c));
      for (int e = 0; e < 3; ++e) {
        const uint32_t parent = mid[kParentSlot[c][e]] - coarse_base;
        const uint32_t child = fine_mid[e] - fine_base;
        if (parent >= coarse_odd || child >= fine_odd) return InternalError("edge tree: midpoint out of range");
        uint32_t& slot = tree->parent[tree->level_offset[j + 1] + child];
        const uint32_t global_parent = tree->level_offset[j] + parent;
        if (slot != kNoParent && slot != global_parent) {
          return InternalError("edge tree: odd vertex with two parents at level " + std::to_string(j + 1));
        }
        slot = global_parent;
      }
    }
  }
  return Status::Ok();
}

// Counting sort of the nodes by parent; children stay in increasing id order.
void BuildChildLists(EdgeTree* tree) {
  const uint32_t n = tree->num_nodes();
  tree->child_begin.assign(static_cast<size_t>(n) + 1, 0);
  for (uint32_t v = 0; v < n; ++v) {
    if (tree->parent[v] != kNoParent) ++tree->child_begin[tree->parent[v] + 1];
  }
  for (uint32_t v = 0; v < n; ++v) tree->child_begin[v + 1] += tree->child_begin[v];
  tree->children.assign(tree->child_begin[n], 0);
  std::vector<uint32_t> fill(tree->child_begin.begin(), tree->child_begin.end() - 1);
  for (uint32_t v = 0; v < n; ++v) {
    if (tree->parent[v] != kNoParent) tree->children[fill[tree->parent[v]]++] = v;
  }
}

}  // namespace

StatusOr<EdgeTree> BuildEdgeTree(const SemiRegularHierarchy& h, int levels) {
  if (levels < 0 || levels > h.levels()) {
    return InvalidArgument("edge tree: " + std::to_string(levels) + " levels requested, hierarchy has " +
                           std::to_string(h.levels()));
  }
  EdgeTree tree;
  tree.levels = levels;
  tree.level_offset.assign(1, 0);
  for (int j = 0; j < levels; ++j) tree.level_offset.push_back(tree.level_offset.back() + h.NumOddVertices(j));
  tree.parent.assign(tree.num_nodes(), kNoParent);
  tree.level.assign(tree.num_nodes(), 0);
  for (int j = 0; j < levels; ++j) {
    for (uint32_t v = tree.level_offset[j]; v < tree.level_offset[j + 1]; ++v) tree.level[v] = static_cast<uint8_t>(j);
  }
  for (int j = 0; j + 1 < levels; ++j) EQMESH_RETURN_IF_ERROR(AssignParents(h, j, &tree));
  for (uint32_t v = tree.num_roots(); v < tree.num_nodes(); ++v) {
    if (tree.parent[v] == kNoParent) return InternalError("edge tree: odd vertex without parent");
  }
  BuildChildLists(&tree);
  return tree;
}

}  // namespace eqmesh::zerotree

// Scan order and causal neighbourhoods of one refinement level for the EQ coder,
// after Lavu, Choi, Baraniuk (SGP 2003), Sec. 3.3, Fig. 12-13: levels are coded
// coarse to fine; inside a level, base triangle after base triangle; inside a base
// triangle, the new vertices in triangular-array order (bottom-left, right along the
// row, then up). The neighbourhood of a vertex is its first three rings of
// same-scale neighbours, across base-triangle borders, restricted to vertices that
// precede it in the scan (causal).
//
// Choices the paper leaves open (normative here, see ext_spec Appendix B):
//  * Base triangles are scanned in breadth-first order over edge-adjacent base faces,
//    starting from the lowest-numbered unvisited face, neighbours taken in the order
//    of the face's edges (v0,v1), (v1,v2), (v2,v0) and, on non-manifold edges, by
//    face index; so every triangle after the first of its component borders an
//    earlier one and finds causal neighbours across that edge.
//  * Each odd vertex is coded once, by the first base triangle (in scan order) whose
//    level-j faces contain it; vertices on base edges shared with an earlier triangle
//    are not rescanned.
//  * The triangle's orientation (which corner is bottom-left, which bottom-right) is
//    the first of the six corner permutations, in the order (0,1,2), (1,2,0), (2,0,1),
//    (0,2,1), (2,1,0), (1,0,2), that maximises the total number of causal first-ring
//    neighbours of its new vertices (a cheap proxy for the paper's "maximise causal
//    same-scale neighbours").
//  * Same-scale neighbours are the odd vertices of level j+1 adjacent in the level
//    j+1 mesh (the edges of the middle children 4f+3); rings are graph distance 1-3.
// Connectivity only: encoder and decoder build identical layouts from the hierarchy.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct EqLevelLayout {
  int level = 0;              // j: codes the odd vertices of level j + 1
  uint32_t first_vertex = 0;  // NumVertices(j); odd index k is vertex first_vertex + k
  std::vector<uint32_t> scan;  // scan position -> odd index
  std::vector<uint32_t> rank;  // odd index -> scan position
  // Causal neighbourhood of scan position i: neighbours[offsets[i] .. offsets[i+1]),
  // given as scan positions (< i), with their ring (1..3) in ring[].
  std::vector<uint32_t> offsets;
  std::vector<uint32_t> neighbours;
  std::vector<uint8_t> ring;

  size_t size() const { return scan.size(); }
};

// Builds the layout of level j -> j+1 (0 <= j < hierarchy.levels()).
StatusOr<EqLevelLayout> BuildEqLevelLayout(const SemiRegularHierarchy& hierarchy, int j);

}  // namespace eqmesh

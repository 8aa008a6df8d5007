// Where a mesh passes through itself: an edge crossing a face that holds
// neither of its ends (a self-intersection, common in assets whose clothes,
// hair or limbs were modelled into each other). Faces that only touch, or
// overlap within one plane, are not counted.
//
// A remesh follows the input's surface, and where two of its sheets pass
// through each other the sheet a point lies on is ambiguous: the remesher's
// fold test and the bench's flipped-face count (quality_checks.h) judge a face
// by the input face nearest its centroid, which there may be the other sheet's.
// These queries let the reports say which folds lie at such places. Each edge
// is cast once through the tree and stops at its first crossing from either
// end, so the work is bounded by the edges, however many faces one crosses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/triangle_bvh.h"

namespace eqmesh {

// Whether an edge of face f crosses a face of `mesh` holding neither of the
// edge's ends. `bvh` is built from `mesh`.
bool EdgeCrossesAnotherFace(const Mesh& mesh, const TriangleBvh& bvh, uint32_t f);

// How many faces have an edge crossing another face (every crossing of two
// faces has at least one); in parallel, the count does not depend on threads.
size_t CountSelfCrossingFaces(const Mesh& mesh, const TriangleBvh& bvh);

// The points where the edges of a mesh cross its faces (the first crossing
// from each end of every crossing edge), for queries by distance.
class SelfCrossingPoints {
 public:
  static StatusOr<SelfCrossingPoints> Find(const Mesh& mesh, const TriangleBvh& bvh);

  size_t size() const { return points_.positions.size(); }
  // Whether one of the points lies within `radius` of p.
  bool Within(const Vec3& p, double radius) const;

 private:
  Mesh points_;  // each point a degenerate face (i, i, i), for the tree
  std::optional<TriangleBvh> tree_;
};

}  // namespace eqmesh

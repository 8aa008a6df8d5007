// Checks of a remesh against its input, for `eqmesh remesh --json` and the
// bench: folded faces (normal opposed to the input's at the closest point of
// the face centroid, on the part the face lies on) and degenerate faces (zero
// area at the input's scale).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct FoldReport {
  size_t flipped_faces = 0;
  // Of those, the faces within kSelfCrossingReach of their longest edge from a
  // place where the input passes through itself (metrics/self_crossings.h).
  size_t flipped_near_self_crossings = 0;
  size_t degenerate_faces = 0;
};

// How near a flipped face (in its longest edges, from its centroid) a crossing
// of the input counts as its neighbourhood: a remesh face near a crossing has
// its corners and centroid within a face or two of it.
inline constexpr double kSelfCrossingReach = 3.0;

// Triangle quality 4*sqrt(3)*area / (sum of squared edge lengths): 1 for an
// equilateral triangle, 0 for a degenerate one.
inline double TriangleQuality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double denom = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(denom > 0.0)) return 0.0;
  return 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / denom;
}

// Faces of lower quality are slivers. The refinement's placement repair looks
// for better-shaped placements of their odd vertices, because a sliver at one
// level leaves slivers at every finer one (its corner children inherit its
// shape), and bands of them at the finest levels are where folds sit. Of 0.05-0.3,
// 0.1 leaves the fewest folds over the bench and small meshes together (measured:
// bench/log/2026-12-05-remesh-notebook.md).
inline constexpr double kSliverQuality = 0.1;

// Faces of `mesh` with TriangleQuality below kSliverQuality.
size_t CountSlivers(const Mesh& mesh);

// Each connected part of `remesh` is judged against the input part most of its
// vertices lie nearest to.
StatusOr<FoldReport> CountFoldsAgainstInput(const Mesh& remesh, const Mesh& input);

// Twice the area at or below which a face of a remesh of `input` counts as
// degenerate (1e-14 of the input's squared bounding-box diagonal).
double DegenerateDoubleArea(const Mesh& input);

class TriangleBvh;

// The part (connected component) of each input face, for the fold test; empty
// when the input is one part, which then takes the plain test.
std::vector<uint32_t> FacePartsForFoldTest(const Mesh& input);

// "No particular part", where a part of the input is asked for.
inline constexpr uint32_t kAnyPart = std::numeric_limits<uint32_t>::max();

// The fold test behind CountFoldsAgainstInput, for one triangle (a, b, c) of
// the remesh of input part `part` (kAnyPart: of the whole input): its normal is
// opposed to that of the part's face closest to its centroid. Adds twice the
// triangle's area times that squared distance to *error when given. Degenerate
// triangles are not folded (CountFoldsAgainstInput counts them apart).
// `face_part`: FacePartsForFoldTest(input). Parts that touch or interpenetrate
// (bones at a joint) put one part's faces nearest the centroids of another's
// remesh faces, facing the other way: against the whole input, those faces
// would count as folded.
bool FacesAwayFromInput(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        uint32_t part, const Vec3& a, const Vec3& b, const Vec3& c, double* error = nullptr);

// What the fold repairs remove: a degenerate triangle (twice its area at most
// `degenerate_double_area`, see DegenerateDoubleArea) or one that faces away.
bool FoldedOrDegenerate(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        uint32_t part, const Vec3& a, const Vec3& b, const Vec3& c, double degenerate_double_area,
                        double* error = nullptr);

// The odd, non-boundary vertices of a remesh, and how many of them are normal.
struct NormalCount {
  size_t normal = 0, counted = 0;
};
NormalCount CountNormal(const SemiRegularHierarchy& hierarchy, const std::vector<VertexKind>& kinds);

// Their normal share (RemeshReport::normal_fraction); 1 when there are none.
double NormalFraction(const SemiRegularHierarchy& hierarchy, const std::vector<VertexKind>& kinds);

}  // namespace eqmesh

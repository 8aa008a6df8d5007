// Fold and degeneracy counts of a remesh (remeshing.md §7 check 2).
#include "remesh/quality_checks.h"

#include <algorithm>
#include <array>
#include <limits>
#include <mutex>

#include <Eigen/Geometry>

#include "core/parallel_for.h"
#include "mesh/mesh_topology.h"
#include "mesh/triangle_bvh.h"

namespace eqmesh {

std::vector<uint32_t> FacePartsForFoldTest(const Mesh& input) {
  const MeshTopology topology(input);
  if (topology.num_components() < 2) return {};
  return topology.FaceComponents();
}

namespace {

// The part under at least two of the corners, else kAnyPart.
uint32_t PartUnderCorners(const TriangleBvh& bvh, const std::vector<uint32_t>& face_part, const Vec3& a,
                          const Vec3& b, const Vec3& c) {
  std::array<uint32_t, 3> part{};
  const std::array<const Vec3*, 3> corners{&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const ClosestPointResult cp = bvh.ClosestPoint(*corners[i]);
    part[i] = cp.found() ? face_part[cp.face] : kAnyPart;
  }
  if (part[0] == part[1] || part[0] == part[2]) return part[0];
  return part[1] == part[2] ? part[1] : kAnyPart;
}

// The input face closest to p, within `reach` first (see FacesAwayFromInput),
// among the faces of `part` unless it is kAnyPart.
ClosestPointResult ClosestOnPart(const TriangleBvh& bvh, const std::vector<uint32_t>& face_part, uint32_t part,
                                 const Vec3& p, double reach) {
  if (part == kAnyPart) {
    ClosestPointResult cp = bvh.ClosestPoint(p, reach);
    return cp.found() ? cp : bvh.ClosestPoint(p);
  }
  const auto on_part = [&](uint32_t f) { return face_part[f] == part; };
  ClosestPointResult cp = bvh.ClosestPointFiltered(p, on_part, reach);
  return cp.found() ? cp : bvh.ClosestPointFiltered(p, on_part);
}

}  // namespace

bool FacesAwayFromInput(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        const Vec3& a, const Vec3& b, const Vec3& c, double* error) {
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 centroid = (a + b + c) / 3.0;
  // The triangle's corners lie on (or near) the input, so the nearest corner
  // bounds the centroid's distance to it: a bounded search prunes most of the
  // tree. A bound that misses (a corner off the surface) falls back to the full
  // search, and a bound never changes which face is found (the traversal
  // order does not depend on it), so the result is the unbounded query's.
  const double reach = std::min({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()}) * (1.0 + 1e-9);
  const uint32_t part = face_part.empty() ? kAnyPart : PartUnderCorners(bvh, face_part, a, b, c);
  const ClosestPointResult cp = ClosestOnPart(bvh, face_part, part, centroid, reach);
  if (!cp.found()) return false;
  if (error) *error += n.norm() * cp.squared_distance;
  const Face& g = input.faces[cp.face];
  const Vec3 m = (input.positions[g[1]] - input.positions[g[0]]).cross(input.positions[g[2]] - input.positions[g[0]]);
  return m.dot(n) < 0.0;
}

bool FoldedOrDegenerate(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        const Vec3& a, const Vec3& b, const Vec3& c, double degenerate_double_area, double* error) {
  if (!((b - a).cross(c - a).norm() > degenerate_double_area)) return true;
  return FacesAwayFromInput(bvh, input, face_part, a, b, c, error);
}

double DegenerateDoubleArea(const Mesh& input) {
  const double diag = BoundingBoxDiagonal(input);
  return 1e-14 * diag * diag;
}

StatusOr<FoldReport> CountFoldsAgainstInput(const Mesh& remesh, const Mesh& input) {
  EQMESH_ASSIGN_OR_RETURN(TriangleBvh bvh, TriangleBvh::Build(input));
  const std::vector<uint32_t> face_part = FacePartsForFoldTest(input);
  const double tiny = DegenerateDoubleArea(input);
  FoldReport total;
  std::mutex lock;
  ParallelFor(remesh.faces.size(), [&](size_t begin, size_t end, size_t) {
    FoldReport local;
    for (size_t i = begin; i < end; ++i) {
      const Face& f = remesh.faces[i];
      const Vec3& a = remesh.positions[f[0]];
      const Vec3& b = remesh.positions[f[1]];
      const Vec3& c = remesh.positions[f[2]];
      const Vec3 n = (b - a).cross(c - a);
      if (n.norm() <= tiny) {
        ++local.degenerate_faces;
        continue;
      }
      if (FacesAwayFromInput(bvh, input, face_part, a, b, c)) ++local.flipped_faces;
    }
    std::lock_guard<std::mutex> guard(lock);
    total.flipped_faces += local.flipped_faces;
    total.degenerate_faces += local.degenerate_faces;
  });
  return total;
}

size_t CountSlivers(const Mesh& mesh) {
  const std::vector<Vec3>& x = mesh.positions;
  size_t slivers = 0;
  for (const Face& f : mesh.faces) slivers += TriangleQuality(x[f[0]], x[f[1]], x[f[2]]) < kSliverQuality;
  return slivers;
}

NormalCount CountNormal(const SemiRegularHierarchy& hierarchy, const std::vector<VertexKind>& kinds) {
  NormalCount c;
  for (size_t v = hierarchy.NumVertices(0); v < kinds.size(); ++v) {
    if (kinds[v] == VertexKind::kBoundary) continue;
    ++c.counted;
    c.normal += kinds[v] == VertexKind::kNormal;
  }
  return c;
}

double NormalFraction(const SemiRegularHierarchy& hierarchy, const std::vector<VertexKind>& kinds) {
  const NormalCount c = CountNormal(hierarchy, kinds);
  return c.counted ? static_cast<double>(c.normal) / static_cast<double>(c.counted) : 1.0;
}

}  // namespace eqmesh

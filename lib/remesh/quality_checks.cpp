// Fold and degeneracy counts of a remesh (remeshing.md §7 check 2).
#include "remesh/quality_checks.h"

#include <algorithm>
#include <map>
#include <mutex>

#include <Eigen/Geometry>

#include "core/parallel_for.h"
#include "mesh/mesh_topology.h"
#include "mesh/triangle_bvh.h"
#include "metrics/self_crossings.h"

namespace eqmesh {

std::vector<uint32_t> FacePartsForFoldTest(const Mesh& input) {
  const MeshTopology topology(input);
  if (topology.num_components() < 2) return {};
  return topology.FaceComponents();
}

namespace {

// The input face closest to p, within `reach` first (see FacesAwayFromInput),
// among the faces of `part` unless it is kAnyPart.
ClosestPointResult ClosestOnPart(const TriangleBvh& bvh, const std::vector<uint32_t>& face_part, uint32_t part,
                                 const Vec3& p, double reach) {
  if (part == kAnyPart || face_part.empty()) {
    ClosestPointResult cp = bvh.ClosestPoint(p, reach);
    return cp.found() ? cp : bvh.ClosestPoint(p);
  }
  const auto on_part = [&](uint32_t f) { return face_part[f] == part; };
  ClosestPointResult cp = bvh.ClosestPoint(p, reach);
  // The nearest face of all, when it is the part's, is the part's nearest.
  if (cp.found() && face_part[cp.face] == part) return cp;
  cp = bvh.ClosestPointFiltered(p, on_part, reach);
  return cp.found() ? cp : bvh.ClosestPointFiltered(p, on_part);
}

}  // namespace

bool FacesAwayFromInput(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        uint32_t part, const Vec3& a, const Vec3& b, const Vec3& c, double* error) {
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 centroid = (a + b + c) / 3.0;
  // The triangle's corners lie on (or near) the input, so the nearest corner
  // bounds the centroid's distance to it: a bounded search prunes most of the
  // tree. A bound that misses (a corner off the surface) falls back to the full
  // search, and a bound never changes which face is found (the traversal
  // order does not depend on it), so the result is the unbounded query's.
  const double reach = std::min({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()}) * (1.0 + 1e-9);
  const ClosestPointResult cp = ClosestOnPart(bvh, face_part, part, centroid, reach);
  if (!cp.found()) return false;
  if (error) *error += n.norm() * cp.squared_distance;
  const Face& g = input.faces[cp.face];
  const Vec3 m = (input.positions[g[1]] - input.positions[g[0]]).cross(input.positions[g[2]] - input.positions[g[0]]);
  return m.dot(n) < 0.0;
}

bool FoldedOrDegenerate(const TriangleBvh& bvh, const Mesh& input, const std::vector<uint32_t>& face_part,
                        uint32_t part, const Vec3& a, const Vec3& b, const Vec3& c, double degenerate_double_area,
                        double* error) {
  if (!((b - a).cross(c - a).norm() > degenerate_double_area)) return true;
  return FacesAwayFromInput(bvh, input, face_part, part, a, b, c, error);
}

double DegenerateDoubleArea(const Mesh& input) {
  const double diag = BoundingBoxDiagonal(input);
  return 1e-14 * diag * diag;
}

namespace {

// Per vertex of `remesh`, the input part its connected part of the remesh is
// judged against (FacesAwayFromInput): the one most of its vertices lie
// nearest to, from at most kPartVotes of them. Empty for a one-part input.
constexpr size_t kPartVotes = 1000;

std::vector<uint32_t> RemeshVertexParts(const Mesh& remesh, const TriangleBvh& bvh,
                                        const std::vector<uint32_t>& face_part) {
  if (face_part.empty()) return {};
  const MeshTopology topology(remesh);
  std::vector<std::vector<uint32_t>> members(topology.num_components());
  std::vector<uint32_t> vertex_component(remesh.positions.size(), MeshTopology::kNone);
  for (size_t f = 0; f < remesh.faces.size(); ++f) {
    for (uint32_t v : remesh.faces[f]) vertex_component[v] = topology.FaceComponents()[f];
  }
  for (uint32_t v = 0; v < vertex_component.size(); ++v) {
    if (vertex_component[v] != MeshTopology::kNone) members[vertex_component[v]].push_back(v);
  }
  std::vector<uint32_t> component_part(members.size(), kAnyPart);
  for (size_t c = 0; c < members.size(); ++c) {
    std::map<uint32_t, size_t> votes;
    const size_t step = std::max<size_t>(1, members[c].size() / kPartVotes);
    for (size_t i = 0; i < members[c].size(); i += step) {
      const ClosestPointResult cp = bvh.ClosestPoint(remesh.positions[members[c][i]]);
      if (cp.found()) ++votes[face_part[cp.face]];
    }
    size_t best = 0;
    for (const auto& [part, count] : votes) {
      if (count > best) best = count, component_part[c] = part;
    }
  }
  std::vector<uint32_t> out(remesh.positions.size(), kAnyPart);
  for (uint32_t v = 0; v < out.size(); ++v) {
    if (vertex_component[v] != MeshTopology::kNone) out[v] = component_part[vertex_component[v]];
  }
  return out;
}

}  // namespace

StatusOr<FoldReport> CountFoldsAgainstInput(const Mesh& remesh, const Mesh& input) {
  EQMESH_ASSIGN_OR_RETURN(TriangleBvh bvh, TriangleBvh::Build(input));
  const std::vector<uint32_t> face_part = FacePartsForFoldTest(input);
  const std::vector<uint32_t> vertex_part = RemeshVertexParts(remesh, bvh, face_part);
  const double tiny = DegenerateDoubleArea(input);
  FoldReport total;
  // Centroid and reach (kSelfCrossingReach) of each flipped face.
  std::vector<std::pair<Vec3, double>> flipped;
  std::mutex lock;
  ParallelFor(remesh.faces.size(), [&](size_t begin, size_t end, size_t) {
    FoldReport local;
    std::vector<std::pair<Vec3, double>> local_flipped;
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
      const uint32_t part = vertex_part.empty() ? kAnyPart : vertex_part[f[0]];
      if (!FacesAwayFromInput(bvh, input, face_part, part, a, b, c)) continue;
      ++local.flipped_faces;
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      local_flipped.push_back({(a + b + c) / 3.0, kSelfCrossingReach * longest});
    }
    std::lock_guard<std::mutex> guard(lock);
    total.flipped_faces += local.flipped_faces;
    total.degenerate_faces += local.degenerate_faces;
    flipped.insert(flipped.end(), local_flipped.begin(), local_flipped.end());
  });
  if (flipped.empty()) return total;
  EQMESH_ASSIGN_OR_RETURN(const SelfCrossingPoints crossings, SelfCrossingPoints::Find(input, bvh));
  for (const auto& [centroid, reach] : flipped) total.flipped_near_self_crossings += crossings.Within(centroid, reach);
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

// Self-crossing queries (self_crossings.h): each edge is cast as a segment
// through the tree, from each end, up to its first hit on a face holding
// neither of the edge's ends (the faces around an end are touched there, not
// crossed).
#include "metrics/self_crossings.h"

#include <algorithm>
#include <array>
#include <utility>

#include "core/parallel_for.h"

namespace eqmesh {

namespace {

// Share of an edge's length at each end where a hit is not a crossing.
constexpr double kEndMargin = 1e-6;

bool Holds(const Face& f, uint32_t v) { return f[0] == v || f[1] == v || f[2] == v; }

using Edge = std::pair<uint32_t, uint32_t>;

Edge Undirected(uint32_t a, uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// The first point, going from a to b, where edge (a, b) crosses a face holding
// neither of its ends.
std::optional<Vec3> FirstCrossing(const Mesh& mesh, const TriangleBvh& bvh, uint32_t a, uint32_t b) {
  const Vec3& pa = mesh.positions[a];
  const Vec3& pb = mesh.positions[b];
  if (!(pa != pb)) return std::nullopt;
  // The ends themselves are left out: a face through an end's position (a
  // vertex duplicated at a seam) touches the edge there, it does not cross it.
  const std::optional<RayHit> hit = bvh.RayFirstHitFiltered(pa, pb - pa, kEndMargin, 1.0 - kEndMargin, [&](uint32_t g) {
    return !Holds(mesh.faces[g], a) && !Holds(mesh.faces[g], b);
  });
  if (!hit) return std::nullopt;
  return Vec3(pa + hit->t * (pb - pa));
}

// Every edge of `mesh` once, sorted.
std::vector<Edge> UniqueEdges(const Mesh& mesh) {
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.faces.size());
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) edges.push_back(Undirected(f[k], f[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

// Per edge of `edges`, the first crossing from each end (none: no crossing).
std::vector<std::array<std::optional<Vec3>, 2>> EdgeCrossings(const Mesh& mesh, const TriangleBvh& bvh,
                                                              const std::vector<Edge>& edges) {
  std::vector<std::array<std::optional<Vec3>, 2>> out(edges.size());
  ParallelFor(edges.size(), [&](size_t begin, size_t end, size_t) {
    for (size_t e = begin; e < end; ++e) {
      out[e][0] = FirstCrossing(mesh, bvh, edges[e].first, edges[e].second);
      if (out[e][0]) out[e][1] = FirstCrossing(mesh, bvh, edges[e].second, edges[e].first);
    }
  });
  return out;
}

}  // namespace

bool EdgeCrossesAnotherFace(const Mesh& mesh, const TriangleBvh& bvh, uint32_t f) {
  const Face& face = mesh.faces[f];
  for (int k = 0; k < 3; ++k) {
    if (FirstCrossing(mesh, bvh, face[k], face[(k + 1) % 3])) return true;
  }
  return false;
}

size_t CountSelfCrossingFaces(const Mesh& mesh, const TriangleBvh& bvh) {
  const std::vector<Edge> edges = UniqueEdges(mesh);
  std::vector<uint8_t> crosses(edges.size(), 0);
  ParallelFor(edges.size(), [&](size_t begin, size_t end, size_t) {
    for (size_t e = begin; e < end; ++e) {
      crosses[e] = FirstCrossing(mesh, bvh, edges[e].first, edges[e].second).has_value();
    }
  });
  const auto crossing = [&](uint32_t a, uint32_t b) {
    const auto it = std::lower_bound(edges.begin(), edges.end(), Undirected(a, b));
    return crosses[static_cast<size_t>(it - edges.begin())] != 0;
  };
  size_t count = 0;
  for (const Face& f : mesh.faces) count += crossing(f[0], f[1]) || crossing(f[1], f[2]) || crossing(f[2], f[0]);
  return count;
}

StatusOr<SelfCrossingPoints> SelfCrossingPoints::Find(const Mesh& mesh, const TriangleBvh& bvh) {
  SelfCrossingPoints out;
  for (const auto& both : EdgeCrossings(mesh, bvh, UniqueEdges(mesh))) {
    for (const std::optional<Vec3>& p : both) {
      if (!p) continue;
      const auto i = static_cast<uint32_t>(out.points_.positions.size());
      out.points_.positions.push_back(*p);
      out.points_.faces.push_back({i, i, i});
    }
  }
  if (out.points_.faces.empty()) return out;
  EQMESH_ASSIGN_OR_RETURN(TriangleBvh tree, TriangleBvh::Build(out.points_));
  out.tree_ = std::move(tree);
  return out;
}

bool SelfCrossingPoints::Within(const Vec3& p, double radius) const {
  return tree_ && tree_->ClosestPoint(p, radius).found();
}

}  // namespace eqmesh

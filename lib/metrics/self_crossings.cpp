// Self-crossing queries (self_crossings.h): each edge is cast as a segment
// through the tree and a hit counts where it lies on a face holding neither of
// the edge's ends (the faces around an end are touched there, not crossed).
#include "metrics/self_crossings.h"

#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "core/parallel_for.h"

namespace eqmesh {

namespace {

bool Holds(const Face& f, uint32_t v) { return f[0] == v || f[1] == v || f[2] == v; }

using Edge = std::pair<uint32_t, uint32_t>;

Edge Undirected(uint32_t a, uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// Whether edge (a, b) crosses a face holding neither end at a point that
// `accept` takes.
template <typename Accept>
bool EdgeCrossesAFace(const Mesh& mesh, const TriangleBvh& bvh, uint32_t a, uint32_t b, const Accept& accept) {
  const Vec3& pa = mesh.positions[a];
  const Vec3& pb = mesh.positions[b];
  if (!(pa != pb)) return false;
  thread_local std::vector<RayHit> hits;
  bvh.RayAllHits(pa, pb - pa, 0.0, 1.0, &hits);
  return std::any_of(hits.begin(), hits.end(), [&](const RayHit& hit) {
    const Face& g = mesh.faces[hit.face];
    return !Holds(g, a) && !Holds(g, b) && accept(Vec3(pa + hit.t * (pb - pa)));
  });
}

bool Anywhere(const Vec3&) { return true; }

}  // namespace

bool EdgeCrossesAnotherFace(const Mesh& mesh, const TriangleBvh& bvh, uint32_t f) {
  const Face& face = mesh.faces[f];
  for (int k = 0; k < 3; ++k) {
    if (EdgeCrossesAFace(mesh, bvh, face[k], face[(k + 1) % 3], Anywhere)) return true;
  }
  return false;
}

size_t CountSelfCrossingFaces(const Mesh& mesh, const TriangleBvh& bvh) {
  // Each edge is cast once, though two faces (or more) hold it.
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.faces.size());
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) edges.push_back(Undirected(f[k], f[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<uint8_t> crosses(edges.size(), 0);
  ParallelFor(edges.size(), [&](size_t begin, size_t end, size_t) {
    for (size_t e = begin; e < end; ++e) crosses[e] = EdgeCrossesAFace(mesh, bvh, edges[e].first, edges[e].second, Anywhere);
  });
  const auto crossing = [&](uint32_t a, uint32_t b) {
    const auto it = std::lower_bound(edges.begin(), edges.end(), Undirected(a, b));
    return crosses[static_cast<size_t>(it - edges.begin())] != 0;
  };
  size_t count = 0;
  for (const Face& f : mesh.faces) count += crossing(f[0], f[1]) || crossing(f[1], f[2]) || crossing(f[2], f[0]);
  return count;
}

bool CrossesItselfNear(const Mesh& mesh, const TriangleBvh& bvh, const Vec3& p, double radius) {
  thread_local std::vector<uint32_t> near;
  bvh.FacesWithin(p, radius, &near);
  const double r2 = radius * radius;
  const auto within = [&](const Vec3& x) { return (x - p).squaredNorm() <= r2; };
  for (uint32_t f : near) {
    const Face& face = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      if (EdgeCrossesAFace(mesh, bvh, face[k], face[(k + 1) % 3], within)) return true;
    }
  }
  return false;
}

}  // namespace eqmesh

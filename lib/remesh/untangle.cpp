// Finest-level fold removal; see untangle.h.
#include "remesh/untangle.h"

#include <algorithm>
#include <optional>

#include <Eigen/Geometry>

#include "mesh/mesh_topology.h"
#include "remesh/quality_checks.h"
#include "wavelet/butterfly.h"

namespace eqmesh {
namespace {

constexpr int kPasses = 4;
// Blends between a vertex's position and its neighbours' centroid that are tried.
constexpr double kBlends[] = {1.0, 0.75, 0.5, 0.25};
constexpr double kMaxErrorGrowth = 2.0;
// Cluster smoothing: rings of neighbours around the folds, Jacobi sweeps.
constexpr int kClusterRings = 2;
constexpr int kClusterIterations = 8;
// Larger clusters are whole folded regions (dragon_vrip's crevices), where a
// Jacobi smoothing is slow and was never kept.
constexpr size_t kMaxClusterVertices = 256;
// Moves of coarser vertices stop short of making the remesh's normal share
// (the remesh bar, bench/README_remesh.md) drop below this.
constexpr double kMinNormalShare = 0.90;

// Edges of `mesh` that only one face uses (its boundary curves), by (min, max).
std::vector<Edge> InputBoundaryEdges(const Mesh& mesh) {
  const MeshTopology topology(mesh);
  std::vector<Edge> boundary;
  for (uint32_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.IsBoundaryEdge(e)) boundary.push_back(topology.EdgeVertices(e));
  }
  return boundary;
}

struct Untangler {
  const std::vector<Face>& faces;
  const InputSurface& surface;
  std::vector<Vec3>& pos;
  std::vector<uint32_t> offsets, incident;  // vertex -> faces (CSR)
  const std::vector<VertexKind>& kinds;
  std::vector<Edge> input_boundary;  // input edges with one face, by LowerX
  double longest_boundary_edge = 0.0;

  Untangler(const std::vector<Face>& finest, const InputSurface& s, std::vector<Vec3>* p,
            const std::vector<VertexKind>& k)
      : faces(finest), surface(s), pos(*p), kinds(k), input_boundary(InputBoundaryEdges(*s.mesh)) {
    const std::vector<Vec3>& x = s.mesh->positions;
    std::sort(input_boundary.begin(), input_boundary.end(), [&](const Edge& e, const Edge& f) {
      return LowerX(e) < LowerX(f) || (LowerX(e) == LowerX(f) && e < f);
    });
    for (const Edge& e : input_boundary) longest_boundary_edge = std::max(longest_boundary_edge, (x[e[1]] - x[e[0]]).norm());
    offsets.assign(pos.size() + 1, 0);
    for (const Face& t : faces) {
      for (uint32_t v : t) ++offsets[v + 1];
    }
    for (size_t v = 0; v < pos.size(); ++v) offsets[v + 1] += offsets[v];
    incident.resize(offsets.back());
    std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
    for (uint32_t f = 0; f < faces.size(); ++f) {
      for (uint32_t v : faces[f]) incident[fill[v]++] = f;
    }
  }

  bool Folded(uint32_t f, double* error) const {
    const Face& t = faces[f];
    const Vec3& a = pos[t[0]];
    const Vec3& b = pos[t[1]];
    const Vec3& c = pos[t[2]];
    if (!((b - a).cross(c - a).squaredNorm() > 0.0)) return true;
    return FacesAwayFromInput(*surface.bvh, *surface.mesh, a, b, c, error);
  }

  // Folded faces around v, then their error (smaller is better).
  std::pair<size_t, double> Score(uint32_t v) const {
    std::pair<size_t, double> s{0, 0.0};
    for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) s.first += Folded(incident[n], &s.second);
    return s;
  }

  // Smaller x of an input edge's endpoints: the key input_boundary is sorted by.
  double LowerX(const Edge& e) const {
    const std::vector<Vec3>& x = surface.mesh->positions;
    return std::min(x[e[0]].x(), x[e[1]].x());
  }

  // Closest point of the input's boundary curves to `target` within `reach`
  // (the edges are sorted by their lower x, so only a slab is scanned).
  std::optional<Vec3> ProjectBoundary(const Vec3& target, double reach) const {
    const std::vector<Vec3>& x = surface.mesh->positions;
    std::optional<Vec3> best;
    double best_d = reach * reach;
    auto it = std::upper_bound(input_boundary.begin(), input_boundary.end(), target.x() + reach,
                               [&](double value, const Edge& e) { return value < LowerX(e); });
    while (it != input_boundary.begin()) {
      const Edge& e = *--it;
      if (LowerX(e) < target.x() - reach - longest_boundary_edge) break;
      const Vec3 a = x[e[0]], d = x[e[1]] - x[e[0]];
      const double len2 = d.squaredNorm();
      const double t = len2 > 0 ? std::clamp((target - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      const Vec3 p = a + t * d;
      const double dist = (p - target).squaredNorm();
      if (dist <= best_d) {
        best_d = dist;
        best = p;
      }
    }
    return best;
  }

  // A boundary vertex slides between its boundary neighbours.
  Vec3 BoundaryNeighbourMidpoint(uint32_t v) const {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    std::vector<uint32_t> seen;
    for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incident[n]]) {
        if (w == v || (kinds[w] != VertexKind::kBoundary && kinds[w] != VertexKind::kBase)) continue;
        if (std::find(seen.begin(), seen.end(), w) != seen.end()) continue;
        seen.push_back(w);
        sum += pos[w];
        ++count;
      }
    }
    return count == 2 ? Vec3(sum / 2.0) : pos[v];
  }

  Vec3 NeighbourCentroid(uint32_t v) const {
    if (kinds[v] == VertexKind::kBoundary) return BoundaryNeighbourMidpoint(v);
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incident[n]]) {
        if (w == v) continue;
        sum += pos[w];
        ++count;
      }
    }
    return count ? Vec3(sum / count) : pos[v];
  }

  // Farthest neighbour of v: the reach of its moves.
  double FanRadius(uint32_t v) const {
    double r = 0.0;
    for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incident[n]]) r = std::max(r, (pos[w] - pos[v]).norm());
    }
    return r;
  }

  // Input point closest to `target` on a triangle facing along `facing`, within
  // `reach` (a filtered search cannot prune by distance alone, so it is bounded).
  ClosestPointResult ProjectFacing(const Vec3& target, const Vec3& facing, double reach) const {
    const std::vector<Vec3>& x = surface.mesh->positions;
    return surface.bvh->ClosestPointFiltered(
        target,
        [&](uint32_t f) {
          const Face& g = surface.mesh->faces[f];
          return (x[g[1]] - x[g[0]]).cross(x[g[2]] - x[g[0]]).dot(facing) > 0.0;
        },
        reach);
  }

  // Orientation of the input where v lies now.
  Vec3 InputNormal(uint32_t v) const {
    const ClosestPointResult cp = surface.bvh->ClosestPoint(pos[v]);
    if (!cp.found()) return Vec3::Zero();
    const Face& g = surface.mesh->faces[cp.face];
    const std::vector<Vec3>& x = surface.mesh->positions;
    return (x[g[1]] - x[g[0]]).cross(x[g[2]] - x[g[0]]);
  }

  // Where v would go for blend t towards its neighbours' centroid: the closest
  // same-facing input point, or the blend itself off the surface.
  std::optional<Vec3> Candidate(uint32_t v, const Vec3& centroid, const Vec3& facing, double t,
                                bool off_surface) const {
    const Vec3 target = (1.0 - t) * pos[v] + t * centroid;
    if (kinds[v] == VertexKind::kBoundary) {
      if (off_surface) return std::nullopt;
      return ProjectBoundary(target, FanRadius(v));
    }
    if (off_surface) return target;
    const ClosestPointResult cp = ProjectFacing(target, facing, FanRadius(v));
    if (!cp.found()) return std::nullopt;
    return cp.point;
  }

  // Moves v to the best candidate if that folds fewer faces; true if moved.
  // Candidates on the input come first; off it only where no surface point
  // helps (at a crease the closest same-facing point of a blend is often the
  // vertex's own place again), a small error for a fold removed.
  bool Improve(uint32_t v) {
    const std::pair<size_t, double> before = Score(v);
    if (before.first == 0) return false;
    const Vec3 start = pos[v];
    const Vec3 centroid = NeighbourCentroid(v);
    const Vec3 facing = InputNormal(v);
    Vec3 best = start;
    std::pair<size_t, double> best_score = before;
    for (const bool off_surface : {false, true}) {
      for (double t : kBlends) {
        const std::optional<Vec3> candidate = Candidate(v, centroid, facing, t, off_surface);
        if (!candidate) continue;
        pos[v] = *candidate;
        const std::pair<size_t, double> score = Score(v);
        pos[v] = start;
        // Fewer folds, but not at any price: the faces' error may grow at most
        // kMaxErrorGrowth-fold (a fold across a thin part is better than a
        // vertex dragged onto the wrong side of it).
        if (score.second > kMaxErrorGrowth * before.second) continue;
        if (score < best_score) {
          best_score = score;
          best = *candidate;
        }
      }
      if (best != start) break;
    }
    pos[v] = best;
    return best != start;
  }

  // Movable vertices within kClusterRings rings of the faces around `folded`
  // that still fold, grouped into connected clusters.
  std::vector<std::vector<uint32_t>> FoldClusters(const std::vector<uint32_t>& folded,
                                                  const std::vector<uint8_t>& movable) const {
    std::vector<uint8_t> in(pos.size(), 0);
    std::vector<uint32_t> seeds;
    for (uint32_t f0 : folded) {
      for (uint32_t v0 : faces[f0]) {
        for (uint32_t n = offsets[v0]; n < offsets[v0 + 1]; ++n) {
          const uint32_t f = incident[n];
          if (!Folded(f, nullptr)) continue;
          for (uint32_t v : faces[f]) {
            if (!in[v]) {
              in[v] = 1;
              seeds.push_back(v);
            }
          }
        }
      }
    }
    std::vector<uint32_t> frontier = seeds, region = seeds;
    for (int ring = 0; ring < kClusterRings; ++ring) {
      std::vector<uint32_t> next;
      for (uint32_t v : frontier) {
        for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
          for (uint32_t w : faces[incident[n]]) {
            if (in[w]) continue;
            in[w] = 1;
            next.push_back(w);
            region.push_back(w);
          }
        }
      }
      frontier = std::move(next);
    }
    std::sort(region.begin(), region.end());
    std::vector<std::vector<uint32_t>> clusters;
    std::vector<uint8_t> done(pos.size(), 0);
    for (uint32_t start : region) {
      if (done[start] || !movable[start]) continue;
      std::vector<uint32_t> cluster{start}, stack{start};
      done[start] = 1;
      while (!stack.empty()) {
        const uint32_t v = stack.back();
        stack.pop_back();
        for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) {
          for (uint32_t w : faces[incident[n]]) {
            if (!in[w] || done[w] || !movable[w]) continue;
            done[w] = 1;
            cluster.push_back(w);
            stack.push_back(w);
          }
        }
      }
      std::sort(cluster.begin(), cluster.end());
      clusters.push_back(std::move(cluster));
    }
    return clusters;
  }

  // Folds and error of the faces around a cluster.
  std::pair<size_t, double> ClusterScore(const std::vector<uint32_t>& cluster) const {
    std::vector<uint32_t> around;
    for (uint32_t v : cluster) {
      for (uint32_t n = offsets[v]; n < offsets[v + 1]; ++n) around.push_back(incident[n]);
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    std::pair<size_t, double> s{0, 0.0};
    for (uint32_t f : around) s.first += Folded(f, &s.second);
    return s;
  }

  // Where single moves are stuck (a pleat needs several vertices to move
  // together), Jacobi-smooths the whole cluster on the surface; kept only if it
  // folds fewer faces without more than kMaxErrorGrowth times the error.
  bool SmoothCluster(const std::vector<uint32_t>& cluster) {
    if (cluster.size() > kMaxClusterVertices) return false;
    const std::pair<size_t, double> before = ClusterScore(cluster);
    if (before.first == 0) return false;
    std::vector<Vec3> saved, next(cluster.size());
    for (uint32_t v : cluster) saved.push_back(pos[v]);
    for (int it = 0; it < kClusterIterations; ++it) {
      for (size_t i = 0; i < cluster.size(); ++i) {
        const uint32_t v = cluster[i];
        const std::optional<Vec3> moved = Candidate(v, NeighbourCentroid(v), InputNormal(v), 1.0, false);
        next[i] = moved ? *moved : pos[v];
      }
      for (size_t i = 0; i < cluster.size(); ++i) pos[cluster[i]] = next[i];
    }
    const std::pair<size_t, double> after = ClusterScore(cluster);
    if (after.first < before.first && after.second <= kMaxErrorGrowth * before.second) return true;
    for (size_t i = 0; i < cluster.size(); ++i) pos[cluster[i]] = saved[i];
    return false;
  }
};

// Vertices at or after `first` that may move: all but base vertices (boundary
// ones slide along the input's boundary curves).
std::vector<uint8_t> MovableFrom(uint32_t first, const std::vector<VertexKind>& kinds) {
  std::vector<uint8_t> movable(kinds.size(), 0);
  for (size_t v = first; v < kinds.size(); ++v) {
    movable[v] = kinds[v] != VertexKind::kBase;
  }
  return movable;
}

// Single-vertex moves, pass after pass, starting from the corners of the faces in
// `folded` that still fold; marks what moved.
void MoveSingleVertices(Untangler* u, const std::vector<uint32_t>& folded,
                        const std::vector<uint8_t>& movable, std::vector<uint8_t>* moved) {
  std::vector<uint8_t> suspect(u->pos.size(), 0);
  for (uint32_t f : folded) {
    if (!u->Folded(f, nullptr)) continue;
    for (uint32_t v : u->faces[f]) suspect[v] = 1;
  }
  for (int pass = 0; pass < kPasses; ++pass) {
    bool changed = false;
    for (uint32_t v = 0; v < u->pos.size(); ++v) {
      if (!suspect[v] || !movable[v]) continue;
      suspect[v] = 0;
      if (!u->Improve(v)) continue;
      changed = true;
      (*moved)[v] = 1;
      // Its neighbours' faces changed: they may now improve too.
      for (uint32_t n = u->offsets[v]; n < u->offsets[v + 1]; ++n) {
        for (uint32_t w : u->faces[u->incident[n]]) suspect[w] = 1;
      }
    }
    if (!changed) break;
  }
}

// Level-j vertices whose position or vertex normal a move changed: the moved
// ones and their level-j one-ring (frame normals blend the stencil's vertex
// normals, butterfly.h).
std::vector<uint8_t> DirtyAtLevel(const SemiRegularHierarchy& h, int j, const std::vector<uint8_t>& moved) {
  std::vector<uint8_t> dirty(h.NumVertices(j), 0);
  for (const Face& f : h.Faces(j)) {
    if (moved[f[0]] || moved[f[1]] || moved[f[2]]) dirty[f[0]] = dirty[f[1]] = dirty[f[2]] = 1;
  }
  return dirty;
}

// A moved vertex is no longer where its prediction's normal put it, nor is any
// later vertex whose prediction or frame a move changed, at every finer
// refinement (a vertex of level j is in the stencils of all later levels): all
// of them become non-normal. Returns how many normal vertices that concerned.
size_t MarkMovedNonNormal(const SemiRegularHierarchy& h, const std::vector<uint8_t>& moved,
                          std::vector<VertexKind>* kinds) {
  std::vector<uint8_t> affected = moved;
  for (int j = 0; j < h.levels(); ++j) {
    const std::vector<uint8_t> dirty = DirtyAtLevel(h, j, moved);
    if (std::find(dirty.begin(), dirty.end(), 1) == dirty.end()) continue;
    const StencilTable stencils = BuildButterflyStencils(h, j);
    const uint32_t first_odd = h.NumVertices(j);
    for (uint32_t k = 0; k < stencils.size(); ++k) {
      for (uint32_t i = stencils.offsets[k]; i < stencils.offsets[k + 1]; ++i) {
        if (dirty[stencils.indices[i]]) affected[first_odd + k] = 1;
      }
    }
  }
  size_t count = 0;
  for (size_t v = 0; v < affected.size(); ++v) {
    if (affected[v] && (*kinds)[v] == VertexKind::kNormal) {
      (*kinds)[v] = VertexKind::kNonNormal;
      ++count;
    }
  }
  return count;
}

// Single moves of the vertices from level `first` on, then cluster smoothing;
// returns the kinds the moves leave (moved vertices and all they enter become
// non-normal) and how many normal vertices that concerned.
std::pair<std::vector<VertexKind>, size_t> UntangleFrom(const SemiRegularHierarchy& h, int first,
                                                        const std::vector<uint32_t>& folded,
                                                        const std::vector<VertexKind>& kinds, Untangler* u) {
  std::vector<uint8_t> moved(u->pos.size(), 0);
  const std::vector<uint8_t> movable = MovableFrom(h.NumVertices(first), kinds);
  MoveSingleVertices(u, folded, movable, &moved);
  for (const std::vector<uint32_t>& cluster : u->FoldClusters(folded, movable)) {
    if (!u->SmoothCluster(cluster)) continue;
    for (uint32_t v : cluster) moved[v] = 1;
  }
  std::vector<VertexKind> out = kinds;
  const size_t marked = MarkMovedNonNormal(h, moved, &out);
  return {std::move(out), marked};
}

}  // namespace

size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const std::vector<uint32_t>& folded, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds) {
  const int levels = hierarchy.levels();
  if (levels < 1 || folded.empty()) return 0;
  Untangler u(hierarchy.Faces(levels), surface, positions, *kinds);
  // Every level may move, as deep as the normal share allows (a coarse vertex's
  // move makes every later vertex predicted from it non-normal); the last two
  // levels always may.
  const std::vector<Vec3> start = *positions;
  const int last_two = std::max(0, levels - 2);
  // A remesh already below the floor (dragon_vrip's) gets the last two levels only.
  const int deepest = NormalFraction(hierarchy, *kinds) >= kMinNormalShare ? 0 : last_two;
  for (int first = deepest;; ++first) {
    auto [trial, marked] = UntangleFrom(hierarchy, first, folded, *kinds, &u);
    if (first >= last_two || NormalFraction(hierarchy, trial) >= kMinNormalShare) {
      *kinds = std::move(trial);
      return marked;
    }
    *positions = start;
  }
}

}  // namespace eqmesh

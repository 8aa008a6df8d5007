// Finest-level fold removal; see untangle.h.
#include "remesh/untangle.h"

#include <Eigen/Geometry>

#include "remesh/quality_checks.h"

namespace eqmesh {
namespace {

constexpr int kPasses = 4;
// Blends between a vertex's position and its neighbours' centroid that are tried.
constexpr double kBlends[] = {1.0, 0.5};
constexpr double kMaxErrorGrowth = 2.0;

struct Untangler {
  const std::vector<Face>& faces;
  const InputSurface& surface;
  std::vector<Vec3>& pos;
  std::vector<uint32_t> offsets, incident;  // vertex -> faces (CSR)

  Untangler(const std::vector<Face>& finest, const InputSurface& s, std::vector<Vec3>* p)
      : faces(finest), surface(s), pos(*p) {
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

  Vec3 NeighbourCentroid(uint32_t v) const {
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

  // Orientation of the input where v lies now.
  Vec3 InputNormal(uint32_t v) const {
    const ClosestPointResult cp = surface.bvh->ClosestPoint(pos[v]);
    if (!cp.found()) return Vec3::Zero();
    const Face& g = surface.mesh->faces[cp.face];
    const std::vector<Vec3>& x = surface.mesh->positions;
    return (x[g[1]] - x[g[0]]).cross(x[g[2]] - x[g[0]]);
  }

  // Moves v to the best candidate if that folds fewer faces; true if moved.
  bool Improve(uint32_t v) {
    const std::pair<size_t, double> before = Score(v);
    if (before.first == 0) return false;
    const Vec3 start = pos[v];
    const Vec3 centroid = NeighbourCentroid(v);
    const Vec3 facing = InputNormal(v);
    const std::vector<Vec3>& x = surface.mesh->positions;
    Vec3 best = start;
    std::pair<size_t, double> best_score = before;
    for (double t : kBlends) {
      const Vec3 target = (1.0 - t) * start + t * centroid;
      const ClosestPointResult cp = surface.bvh->ClosestPointFiltered(target, [&](uint32_t f) {
        const Face& g = surface.mesh->faces[f];
        return (x[g[1]] - x[g[0]]).cross(x[g[2]] - x[g[0]]).dot(facing) > 0.0;
      });
      if (!cp.found()) continue;
      pos[v] = cp.point;
      const std::pair<size_t, double> score = Score(v);
      // Fewer folds, but not at any price: the faces' error may grow at most
      // kMaxErrorGrowth-fold (a fold across a thin part is better than a
      // vertex dragged onto the wrong side of it).
      if (score.second > kMaxErrorGrowth * before.second) continue;
      if (score < best_score) {
        best_score = score;
        best = cp.point;
      }
    }
    pos[v] = best;
    return best != start;
  }
};

}  // namespace

size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const std::vector<uint32_t>& folded, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds) {
  const int levels = hierarchy.levels();
  if (levels < 1 || folded.empty()) return 0;
  const uint32_t first_odd = hierarchy.NumVertices(levels - 1);
  Untangler u(hierarchy.Faces(levels), surface, positions);
  std::vector<uint8_t> suspect(positions->size(), 0);
  for (uint32_t f : folded) {
    for (uint32_t v : u.faces[f]) suspect[v] = 1;
  }
  size_t moved = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool changed = false;
    for (uint32_t v = first_odd; v < positions->size(); ++v) {
      if (!suspect[v] || (*kinds)[v] == VertexKind::kBoundary) continue;
      suspect[v] = 0;
      if (!u.Improve(v)) continue;
      changed = true;
      if ((*kinds)[v] != VertexKind::kNonNormal) {
        (*kinds)[v] = VertexKind::kNonNormal;
        ++moved;
      }
      // Its neighbours' faces changed: they may now improve too.
      for (uint32_t n = u.offsets[v]; n < u.offsets[v + 1]; ++n) {
        for (uint32_t w : u.faces[u.incident[n]]) suspect[w] = 1;
      }
    }
    if (!changed) break;
  }
  return moved;
}

}  // namespace eqmesh

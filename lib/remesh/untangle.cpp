// Finest-level fold removal; see untangle.h.
#include "remesh/untangle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>

#include "remesh/face_incidence.h"
#include "remesh/fan_kernel.h"
#include "remesh/patch_flattening.h"
#include "remesh/quality_checks.h"
#include "remesh/stencil_cache.h"

namespace eqmesh {
namespace {

constexpr int kPasses = 4;
// Blends between a vertex's position and its neighbours' centroid that are tried.
constexpr double kBlends[] = {1.0, 0.75, 0.5, 0.25};
constexpr double kMaxErrorGrowth = 2.0;
// Error every move may reach whatever the start: faces whose centroids sit this
// share of their longest edge off the input. Without it a fold lying flat in one
// input triangle (error 0, common at the finest level, whose faces are smaller
// than the input's) could only be moved to error 0, i.e. never.
constexpr double kErrorFloorShare = 0.05;
// Cluster smoothing: rings of neighbours around the folds, widened round after
// round (one wide ring count for all merged neighbouring folds, and a merged
// cluster is kept or undone as a whole: measured worse than widening).
constexpr int kClusterRings[] = {2, 3, 4, 6};
// Sweeps per cluster: Jacobi to the centroids, Gauss-Seidel to the kernel
// centres (96 gain nothing over 48 on the bench meshes), ending after
// kStallSweeps without fewer folds (12 is too short: armadillo 48 folds, not 4).
constexpr int kClusterIterations = 8;
constexpr int kKernelIterations = 48;
constexpr int kStallSweeps = 24;
// The untangler's whole budget, in fold tests per finest face: the bench meshes
// spend 0.12-0.19, while dragon_vrip (thousands of folded crevices no move
// unfolds) would spend 7.8 and double its remesh time. Counted, not timed, so
// the result does not depend on the machine; past it, no more moves are tried.
constexpr double kWorkPerFace = 1.0;
// Larger clusters are whole folded regions (dragon_vrip's crevices), where a
// sweep is slow and never kept (2,048 changes nothing on the bench meshes).
constexpr size_t kMaxClusterVertices = 512;
// Moves of coarser vertices stop short of making the remesh's normal share
// (the remesh bar, bench/README_remesh.md) drop below this ...
constexpr double kMinNormalShare = 0.90;
// ... and in the final pass below this: a fold that pass leaves stays in the
// remesh, while a non-normal vertex costs two coefficients, so it may spend
// more of the share (measured: bench/log/2026-12-06-parts-and-fold-floors.md).
// The per-level passes keep the higher floor: their moves make every later
// vertex predicted from the moved one non-normal.
constexpr double kMinFinalNormalShare = 0.80;
// Rounds of MoveCornersOfNewFolds, each seeded with what still folds.
constexpr int kCleanupRounds = 4;

struct Untangler {
  const std::vector<Face>& faces;
  int level;  // of `faces`, the finest
  const InputSurface& surface;
  const RemeshParts& parts;
  std::vector<Vec3>& pos;
  FaceIncidence incidence;  // vertex -> finest faces
  const std::vector<VertexKind>& kinds;
  double degenerate_double_area;
  // Fold tests the untangler may still make (kWorkPerFace).
  mutable size_t work_left = 0;
  LevelUse use = LevelUse::kFinal;
  // Cluster sweeps that failed, by everything they read (SweepInput) and the
  // sweep kind, with the work they spent. The same cluster from the same
  // positions fails the same way, and the ring widths, level trials and
  // cleanup rounds ask again (failed repeats: skull 14 of 49 sweeps, half the
  // sweeps' time; horse 16 of 50; armadillo 16 of 107). A repeat is answered
  // from here and charged the same work, so the budget runs out where a rerun's would.
  std::map<std::pair<std::vector<uint64_t>, bool>, size_t> failed_sweeps;

  Untangler(const SemiRegularHierarchy& h, const InputSurface& s, const RemeshParts& remesh_parts,
            std::vector<Vec3>* p, const std::vector<VertexKind>& k)
      : faces(h.Faces(h.levels())),
        level(h.levels()),
        surface(s),
        parts(remesh_parts),
        pos(*p),
        kinds(k),
        degenerate_double_area(DegenerateDoubleArea(*s.mesh)),
        work_left(static_cast<size_t>(kWorkPerFace * static_cast<double>(faces.size()))) {
    incidence = BuildFaceIncidence(faces, pos.size());
  }

  // The normal share the moves and refills of this pass keep.
  double ShareFloor() const { return use == LevelUse::kFinal ? kMinFinalNormalShare : kMinNormalShare; }

  // The last fold test of each face, by its corners bit for bit: a quarter of
  // the tests repeat one (man: 3.4M of 15M), since scores before and after a
  // move, cluster scans and sweeps ask about the same faces again. A repeat is
  // charged as work like any test, so the moves do not depend on the memo.
  struct FoldTest {
    std::array<Vec3, 3> corners;
    bool folded;
    double error;
  };
  mutable std::unordered_map<uint32_t, FoldTest> tested;

  bool Folded(uint32_t f, double* error) const {
    if (work_left > 0) --work_left;
    const Face& t = faces[f];
    const std::array<Vec3, 3> corners{pos[t[0]], pos[t[1]], pos[t[2]]};
    auto it = tested.find(f);
    // Bit for bit: -0.0 and 0.0 compare equal but need not test the same.
    if (it == tested.end() || std::memcmp(it->second.corners.data(), corners.data(), sizeof corners) != 0) {
      double e = 0.0;
      // A degenerate face is as bad as a folded one (the bench counts both).
      const bool folded = FoldedOrDegenerate(*surface.bvh, *surface.mesh, surface.face_part, parts.Of(f, level),
                                             corners[0], corners[1], corners[2], degenerate_double_area, &e);
      it = tested.insert_or_assign(f, FoldTest{corners, folded, e}).first;
    }
    if (error) *error += it->second.error;
    return it->second.folded;
  }

  // Error allowance of face f for kErrorFloorShare (same units as Folded's).
  double ErrorFloor(uint32_t f) const {
    const Face& t = faces[f];
    const Vec3& a = pos[t[0]];
    const Vec3& b = pos[t[1]];
    const Vec3& c = pos[t[2]];
    const double reach = kErrorFloorShare * std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    return (b - a).cross(c - a).norm() * reach * reach;
  }

  double FanErrorFloor(uint32_t v) const {
    double floor = 0.0;
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      floor += ErrorFloor(incidence.faces[n]);
    }
    return floor;
  }

  // Folded faces around v, then their error (smaller is better).
  std::pair<size_t, double> Score(uint32_t v) const {
    std::pair<size_t, double> s{0, 0.0};
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      s.first += Folded(incidence.faces[n], &s.second);
    }
    return s;
  }

  // A boundary vertex slides between its boundary neighbours.
  Vec3 BoundaryNeighbourMidpoint(uint32_t v) const {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    std::vector<uint32_t> seen;
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incidence.faces[n]]) {
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
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incidence.faces[n]]) {
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
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      for (uint32_t w : faces[incidence.faces[n]]) r = std::max(r, (pos[w] - pos[v]).norm());
    }
    return r;
  }

  // Input point closest to `target` on a triangle facing along `facing`, within
  // `reach` (a filtered search cannot prune by distance alone, so it is bounded).
  ClosestPointResult ProjectFacing(const Vec3& target, const Vec3& facing, double reach) const {
    return surface.bvh->ClosestPointFiltered(
        target, [&](uint32_t f) { return surface.face_normals[f].dot(facing) > 0.0; }, reach);
  }

  // Orientation of the input where v lies now.
  Vec3 InputNormal(uint32_t v) const {
    const ClosestPointResult cp = surface.bvh->ClosestPoint(pos[v]);
    if (!cp.found()) return Vec3::Zero();
    return surface.face_normals[cp.face];
  }

  // Where v would go for blend t towards `aim`: the closest
  // same-facing input point, or the blend itself off the surface.
  std::optional<Vec3> Candidate(uint32_t v, const Vec3& aim, const Vec3& facing, double t,
                                bool off_surface) const {
    const Vec3 target = (1.0 - t) * pos[v] + t * aim;
    if (kinds[v] == VertexKind::kBoundary) {
      if (off_surface) return std::nullopt;
      return surface.ClosestBoundaryPoint(target, FanRadius(v));
    }
    if (off_surface) return target;
    const ClosestPointResult cp = ProjectFacing(target, facing, FanRadius(v));
    if (!cp.found()) return std::nullopt;
    return cp.point;
  }

  // The point of v's flattened fan farthest from inverting any of its faces.
  std::optional<Vec3> KernelCentre(uint32_t v, const Vec3& facing) const {
    std::vector<std::pair<Vec3, Vec3>> opposite;
    for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
      const Face& t = faces[incidence.faces[n]];
      const int c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      opposite.emplace_back(pos[t[(c + 1) % 3]], pos[t[(c + 2) % 3]]);
    }
    return FanKernelCenter(pos[v], facing, opposite);
  }

  // Moves v to the best candidate if that folds fewer faces; true if moved.
  // Candidates on the input come first; off it only where no surface point
  // helps (at a crease the closest same-facing point of a blend is often the
  // vertex's own place again), a small error for a fold removed.
  bool Improve(uint32_t v) {
    if (work_left == 0) return false;
    const std::pair<size_t, double> before = Score(v);
    if (before.first == 0) return false;
    const Vec3 start = pos[v];
    const Vec3 centroid = NeighbourCentroid(v);
    const Vec3 facing = InputNormal(v);
    const double allowed = std::max(kMaxErrorGrowth * before.second, FanErrorFloor(v));
    // Interior vertices also aim at their fan's kernel centre, which undoes
    // folds the centroid cannot (a face turned over inside one input triangle).
    std::vector<Vec3> aims{centroid};
    if (kinds[v] != VertexKind::kBoundary) {
      if (const std::optional<Vec3> kernel = KernelCentre(v, facing)) aims.push_back(*kernel);
    }
    Vec3 best = start;
    std::pair<size_t, double> best_score = before;
    for (const bool off_surface : {false, true}) {
      if (off_surface && use == LevelUse::kPiercedFrom) break;
      for (const Vec3& aim : aims) {
        for (double t : kBlends) {
          const std::optional<Vec3> candidate = Candidate(v, aim, facing, t, off_surface);
          if (!candidate) continue;
          pos[v] = *candidate;
          const std::pair<size_t, double> score = Score(v);
          pos[v] = start;
          // Fewer folds, but not at any price: the faces' error may grow at
          // most kMaxErrorGrowth-fold, or to the floor (a fold across a thin
          // part is better than a vertex dragged onto the wrong side of it).
          if (score.second > allowed) continue;
          if (score < best_score) {
            best_score = score;
            best = *candidate;
          }
        }
      }
      if (best != start) break;
    }
    pos[v] = best;
    return best != start;
  }

  // Movable vertices within `rings` rings of the faces around `folded`
  // that still fold, grouped into connected clusters.
  std::vector<std::vector<uint32_t>> FoldClusters(const std::vector<uint32_t>& folded,
                                                  const std::vector<uint8_t>& movable, int rings) const {
    std::vector<uint8_t> in(pos.size(), 0);
    std::vector<uint32_t> seeds;
    for (uint32_t f0 : folded) {
      for (uint32_t v0 : faces[f0]) {
        for (uint32_t n = incidence.offsets[v0]; n < incidence.offsets[v0 + 1]; ++n) {
          const uint32_t f = incidence.faces[n];
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
    for (int ring = 0; ring < rings; ++ring) {
      std::vector<uint32_t> next;
      for (uint32_t v : frontier) {
        for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
          for (uint32_t w : faces[incidence.faces[n]]) {
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
        for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
          for (uint32_t w : faces[incidence.faces[n]]) {
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

  std::vector<uint32_t> FacesAround(const std::vector<uint32_t>& cluster) const {
    std::vector<uint32_t> around;
    for (uint32_t v : cluster) {
      for (uint32_t n = incidence.offsets[v]; n < incidence.offsets[v + 1]; ++n) {
        around.push_back(incidence.faces[n]);
      }
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    return around;
  }

  // Folds and error of `around` (the faces around a cluster).
  std::pair<size_t, double> FacesScore(const std::vector<uint32_t>& around) const {
    std::pair<size_t, double> s{0, 0.0};
    for (uint32_t f : around) s.first += Folded(f, &s.second);
    return s;
  }

  // Where single moves are stuck (a pleat needs several vertices to move
  // together), Jacobi-smooths the whole cluster on the surface, or with
  // `to_kernel` sweeps it towards its fans' kernel centres; keeps the best
  // iterate if it folds fewer faces without more than kMaxErrorGrowth times
  // the error (or the floor).
  bool SmoothCluster(const std::vector<uint32_t>& cluster, bool to_kernel) {
    if (cluster.size() > kMaxClusterVertices || work_left == 0) return false;
    const std::vector<uint32_t> around = FacesAround(cluster);
    std::pair<std::vector<uint64_t>, bool> key{SweepInput(cluster, around), to_kernel};
    const auto known = failed_sweeps.find(key);
    // Only a sweep the budget did not cut short is replayed, and only where it
    // would not be cut short now.
    if (known != failed_sweeps.end() && work_left > known->second) {
      work_left -= known->second;
      return false;
    }
    const size_t work_before = work_left;
    const bool improved = SweepCluster(cluster, around, to_kernel);
    if (!improved && work_left > 0) failed_sweeps.emplace(std::move(key), work_before - work_left);
    return improved;
  }

  // What a cluster sweep depends on besides the input: the cluster and every
  // vertex of the faces around it (`around`), with its position bit for bit.
  std::vector<uint64_t> SweepInput(const std::vector<uint32_t>& cluster, const std::vector<uint32_t>& around) const {
    std::vector<uint64_t> key(cluster.begin(), cluster.end());
    key.push_back(~uint64_t{0});  // separates the two parts
    for (uint32_t f : around) {
      for (uint32_t v : faces[f]) {
        key.push_back(v);
        for (int k = 0; k < 3; ++k) {
          uint64_t bits;
          std::memcpy(&bits, &pos[v][k], sizeof bits);
          key.push_back(bits);
        }
      }
    }
    return key;
  }

  // SmoothCluster's sweeps, always run; `around`: FacesAround(cluster).
  bool SweepCluster(const std::vector<uint32_t>& cluster, const std::vector<uint32_t>& around, bool to_kernel) {
    const std::pair<size_t, double> before = FacesScore(around);
    if (before.first == 0) return false;
    double floor = 0.0;
    for (uint32_t f : around) floor += ErrorFloor(f);
    const double allowed = std::max(kMaxErrorGrowth * before.second, floor);
    // The fold count does not fall monotonically along the sweeps: the best
    // iterate is kept (at first the start), not the last; sweeps end when all
    // folds are gone or kStallSweeps found nothing better.
    std::vector<Vec3> best, next(cluster.size());
    for (uint32_t v : cluster) best.push_back(pos[v]);
    std::pair<size_t, double> best_score = before;
    const int sweeps = to_kernel ? kKernelIterations : kClusterIterations;
    for (int it = 0, stalled = 0; it < sweeps && best_score.first > 0 && stalled < kStallSweeps && work_left > 0;
         ++it) {
      for (size_t i = 0; i < cluster.size(); ++i) {
        const uint32_t v = cluster[i];
        // The input's orientation where v is now (a sweep may carry it over a crease).
        const Vec3 facing = InputNormal(v);
        std::optional<Vec3> aim;
        if (to_kernel && kinds[v] != VertexKind::kBoundary) aim = KernelCentre(v, facing);
        const std::optional<Vec3> moved = Candidate(v, aim ? *aim : NeighbourCentroid(v), facing, 1.0, false);
        next[i] = moved ? *moved : pos[v];
        // Kernel sweeps run in place (Gauss-Seidel): each centre needs the
        // neighbours' latest positions to untangle a multi-vertex fold.
        if (to_kernel) pos[v] = next[i];
      }
      for (size_t i = 0; i < cluster.size(); ++i) pos[cluster[i]] = next[i];
      const std::pair<size_t, double> score = FacesScore(around);
      ++stalled;
      if (score.second <= allowed && score < best_score) {
        if (score.first < best_score.first) stalled = 0;
        best_score = score;
        best = next;
      }
    }
    for (size_t i = 0; i < cluster.size(); ++i) pos[cluster[i]] = best[i];
    return best_score.first < before.first;
  }
};

// Vertices at or after `first` that may move: all but base vertices, and
// boundary ones (which slide along the input's boundary curves) only on the
// final level (LevelUse).
std::vector<uint8_t> MovableFrom(uint32_t first, const std::vector<VertexKind>& kinds, LevelUse use) {
  std::vector<uint8_t> movable(kinds.size(), 0);
  for (size_t v = first; v < kinds.size(); ++v) {
    movable[v] = kinds[v] != VertexKind::kBase &&
                 (kinds[v] != VertexKind::kBoundary || use == LevelUse::kFinal);
  }
  return movable;
}

// Normal vertices a move may still turn non-normal; unlimited when absent.
class NormalBudget {
 public:
  explicit NormalBudget(std::optional<size_t> left) : left_(left) {}
  // 1 if v is normal and not moved yet: what moving it costs.
  static size_t Cost(uint32_t v, const std::vector<VertexKind>& kinds, const std::vector<uint8_t>& moved) {
    return kinds[v] == VertexKind::kNormal && !moved[v];
  }
  static size_t Cost(const std::vector<uint32_t>& vertices, const std::vector<VertexKind>& kinds,
                     const std::vector<uint8_t>& moved) {
    size_t cost = 0;
    for (uint32_t v : vertices) cost += Cost(v, kinds, moved);
    return cost;
  }
  bool Affords(size_t cost) const { return !left_ || cost <= *left_; }
  void Spend(size_t cost) {
    if (left_) *left_ -= cost;
  }

 private:
  std::optional<size_t> left_;
};

// Single-vertex moves, pass after pass, starting from the corners of the faces in
// `folded` that still fold, within `budget`; marks what moved.
void MoveSingleVertices(Untangler* u, const std::vector<uint32_t>& folded, const std::vector<uint8_t>& movable,
                        NormalBudget* budget, std::vector<uint8_t>* moved) {
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
      const size_t cost = NormalBudget::Cost(v, u->kinds, *moved);
      if (!budget->Affords(cost) || !u->Improve(v)) continue;
      budget->Spend(cost);
      changed = true;
      (*moved)[v] = 1;
      // Its neighbours' faces changed: they may now improve too.
      for (uint32_t n = u->incidence.offsets[v]; n < u->incidence.offsets[v + 1]; ++n) {
        for (uint32_t w : u->faces[u->incidence.faces[n]]) suspect[w] = 1;
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
                          StencilCache* cache, std::vector<VertexKind>* kinds) {
  std::vector<uint8_t> affected = moved;
  for (int j = 0; j < h.levels(); ++j) {
    const std::vector<uint8_t> dirty = DirtyAtLevel(h, j, moved);
    if (std::find(dirty.begin(), dirty.end(), 1) == dirty.end()) continue;
    const StencilTable& stencils = cache->Level(j);
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
                                                        const std::vector<VertexKind>& kinds,
                                                        std::optional<size_t> budget_left, StencilCache* cache,
                                                        Untangler* u) {
  std::vector<uint8_t> moved(u->pos.size(), 0);
  const std::vector<uint8_t> movable = MovableFrom(h.NumVertices(first), kinds, u->use);
  NormalBudget budget(budget_left);
  // A smoothed cluster can leave folds single moves then undo.
  for (const int rings : kClusterRings) {
    MoveSingleVertices(u, folded, movable, &budget, &moved);
    for (const std::vector<uint32_t>& cluster : u->FoldClusters(folded, movable, rings)) {
      const size_t cost = NormalBudget::Cost(cluster, kinds, moved);
      if (!budget.Affords(cost)) continue;
      if (!u->SmoothCluster(cluster, false) && !u->SmoothCluster(cluster, true)) continue;
      budget.Spend(cost);
      for (uint32_t v : cluster) moved[v] = 1;
    }
  }
  MoveSingleVertices(u, folded, movable, &budget, &moved);
  std::vector<VertexKind> out = kinds;
  const size_t marked = MarkMovedNonNormal(h, moved, cache, &out);
  return {std::move(out), marked};
}

// How many normal vertices may turn non-normal before the share drops below
// `share_floor` (NormalFraction's count).
size_t NormalsAboveFloor(const SemiRegularHierarchy& h, const std::vector<VertexKind>& kinds, double share_floor) {
  const NormalCount c = CountNormal(h, kinds);
  const auto floor = static_cast<size_t>(std::ceil(share_floor * static_cast<double>(c.counted)));
  return c.normal > floor ? c.normal - floor : 0;
}

// Faces that may still fold: those that folded, and those around a moved vertex.
std::vector<uint32_t> MaybeFolded(const Untangler& u, const std::vector<uint32_t>& folded,
                                  const std::vector<Vec3>& start) {
  std::vector<uint32_t> faces = folded;
  for (uint32_t v = 0; v < u.pos.size(); ++v) {
    if (u.pos[v] == start[v]) continue;
    const auto& around = u.incidence;
    faces.insert(faces.end(), around.faces.begin() + around.offsets[v], around.faces.begin() + around.offsets[v + 1]);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

// The untangling of UntangleFinestLevel without the patch refills.
// `start`: the positions as the remesh came, which every trial starts from.
size_t MoveFoldedCorners(const SemiRegularHierarchy& hierarchy, const std::vector<uint32_t>& folded,
                         const std::vector<Vec3>& start, StencilCache* cache, std::vector<VertexKind>* kinds,
                         Untangler* u) {
  const int levels = hierarchy.levels();
  std::vector<Vec3>* positions = &u->pos;
  // Every level may move, as deep as the normal share allows (a coarse vertex's
  // move makes every later vertex predicted from it non-normal). The finest
  // level alone comes last, with a budget: its moves enter no stencil, so each
  // costs one normal vertex, and they stop where the share would reach the floor.
  const int last_two = std::max(0, levels - 2);
  if (NormalFraction(hierarchy, *kinds) < u->ShareFloor()) {
    // A remesh already below the floor (dragon_vrip's): the last two levels, freely.
    auto [trial, marked] = UntangleFrom(hierarchy, last_two, folded, *kinds, std::nullopt, cache, u);
    *kinds = std::move(trial);
    return marked;
  }
  for (int first = 0; first < levels - 1; ++first) {
    auto [trial, marked] = UntangleFrom(hierarchy, first, folded, *kinds, std::nullopt, cache, u);
    if (NormalFraction(hierarchy, trial) >= u->ShareFloor()) {
      *kinds = std::move(trial);
      return marked;
    }
    *positions = start;
  }
  const size_t budget = NormalsAboveFloor(hierarchy, *kinds, u->ShareFloor());
  auto [trial, marked] = UntangleFrom(hierarchy, levels - 1, folded, *kinds, budget, cache, u);
  *kinds = std::move(trial);
  return marked;
}

// The faces of MaybeFolded that fold now.
std::vector<uint32_t> StillFolded(const Untangler& u, const std::vector<uint32_t>& folded,
                                  const std::vector<Vec3>& start) {
  std::vector<uint32_t> now;
  for (uint32_t f : MaybeFolded(u, folded, start)) {
    if (u.Folded(f, nullptr)) now.push_back(f);
  }
  return now;
}

// Cluster sweeps and patch refills may fold faces that the moves, seeded with
// the refinement's folds, never looked at (skull: 7 folds, 6 of them such).
// More rounds of moves at every level, each seeded with the faces that fold
// now; a round is kept only while the normal share stays at the floor (or
// where it was, if already below).
size_t MoveCornersOfNewFolds(const SemiRegularHierarchy& hierarchy, const std::vector<uint32_t>& folded,
                             const std::vector<Vec3>& start, StencilCache* cache, std::vector<VertexKind>* kinds,
                             Untangler* u) {
  size_t marked = 0;
  std::vector<uint32_t> now = StillFolded(*u, folded, start);
  for (int round = 0; round < kCleanupRounds && !now.empty(); ++round) {
    const std::vector<Vec3> before = u->pos;
    const double share_floor = std::min(u->ShareFloor(), NormalFraction(hierarchy, *kinds));
    auto [trial, round_marked] =
        UntangleFrom(hierarchy, 0, now, *kinds, NormalsAboveFloor(hierarchy, *kinds, u->ShareFloor()), cache, u);
    if (NormalFraction(hierarchy, trial) < share_floor) {
      u->pos = before;
      break;
    }
    *kinds = std::move(trial);
    marked += round_marked;
    const size_t count = now.size();
    now = StillFolded(*u, folded, start);
    if (now.size() >= count) break;
  }
  return marked;
}

}  // namespace

size_t UntangleFinestLevel(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                           const RemeshParts& parts, const std::vector<uint32_t>& folded,
                           const std::vector<StencilTable>& built, std::vector<Vec3>* positions,
                           std::vector<VertexKind>* kinds, LevelUse use, std::vector<uint32_t>* still_folded) {
  if (still_folded) still_folded->clear();
  if (hierarchy.levels() < 1 || folded.empty()) return 0;
  Untangler u(hierarchy, surface, parts, positions, *kinds);
  u.use = use;
  const std::vector<Vec3> start = *positions;
  StencilCache stencils(hierarchy, built);
  size_t marked = MoveFoldedCorners(hierarchy, folded, start, &stencils, kinds, &u);
  // The refills' non-normal vertices may not take the share below the floor
  // the moves kept: then they are undone as a whole.
  const std::vector<Vec3> moved_only = *positions;
  std::vector<VertexKind> refilled_kinds = *kinds;
  const std::vector<uint8_t> refilled = FlattenFoldedPatches(
      hierarchy, surface, parts, *kinds, MaybeFolded(u, folded, start), u.incidence, &stencils, positions);
  const size_t refill_marked = MarkMovedNonNormal(hierarchy, refilled, &stencils, &refilled_kinds);
  if (NormalFraction(hierarchy, refilled_kinds) < u.ShareFloor() &&
      NormalFraction(hierarchy, *kinds) >= u.ShareFloor()) {
    *positions = moved_only;
  } else {
    *kinds = std::move(refilled_kinds);
    marked += refill_marked;
  }
  marked += MoveCornersOfNewFolds(hierarchy, folded, start, &stencils, kinds, &u);
  if (still_folded) *still_folded = StillFolded(u, folded, start);
  return marked;
}

}  // namespace eqmesh

// MAPS base domain by half-edge collapses (Lee et al. 1998). See base_domain.h for
// the departures from MAPS; the collapse cost is described at Candidates().
#include "remesh/base_domain.h"

#include <algorithm>
#include <array>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>

#include <Eigen/Core>

#include "mesh/mesh_topology.h"
#include "mesh/triangle_bvh.h"
#include "core/parallel_for.h"
#include "remesh/quality_checks.h"
#include "remesh/ring_flattening.h"
#include "core/spin_team.h"

namespace eqmesh {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
// Threads that re-cost a collapse's ring (about 6 vertices) and test its new fan
// against the input (one closest-point query per wedge): more would mostly wait.
constexpr int kTeamWorkers = 2;
constexpr size_t kMaxValence = 12;
// A collapse may not turn a face by more than ~80 degrees (no normal flips).
constexpr double kMinNormalCos = 0.17;
// Minimum 3D triangle quality 4*sqrt(3)*A / sum(l^2) a collapse may create,
// unless the star already holds a worse triangle. It stays where the simplification
// stalls: the slivers would cost more than the smaller base saves (measured:
// bench/log/2026-12-05-remesh-notebook.md).
constexpr double kMinQuality = 0.08;
// Quality floor in that division, so a degenerate fan stays finite.
constexpr double kQualityFloor = 1e-3;
// Cost of a collapse that would fold the base against the input or take an
// input vertex beyond the error bound: refused.
constexpr double kRefusedCost = std::numeric_limits<double>::infinity();
// RaiseValenceThree flips only at tips: valence-3 vertices whose faces' angles
// at them sum to less than this (radians; 300 degrees, a flat vertex has 360).
constexpr double kPi = 3.14159265358979323846;
constexpr double kTipAngleSum = 300.0 * kPi / 180.0;

struct Ring {
  std::vector<uint32_t> verts;  // k_0..k_{d-1}, counter-clockwise around v
  std::vector<uint32_t> faces;  // faces[m] = (v, k_m, k_{m+1}) up to rotation
  bool closed = false;
};

// Buffers of Candidates / CollapseCost, reused because they run once per queued
// vertex and dominate the simplification's time; one per thread.
struct FanTriangle {
  Eigen::Matrix2d to_weights;  // chart offset from the collapse target -> weights of the other corners
  Vec3 to_a, to_b;             // 3D offsets of those corners from the target
};
struct CostScratch {
  std::vector<FanTriangle> fan;
  std::vector<Vec3> facing, ring_pos, items, normals;
  std::vector<Vec2> z, chart;
  std::vector<std::pair<double, size_t>> order;  // targets by fan quality
  Ring ring;                                     // of the vertex being re-costed
  uint32_t centre = 0;                           // the vertex Candidates costs
};

struct QueueEntry {
  double cost;
  uint32_t vertex;
  uint32_t stamp;
  bool operator<(const QueueEntry& o) const { return cost > o.cost; }  // min-heap
};

// Round-off can leave a point a hair outside every triangle of a chart: its
// barycentrics are clamped to the triangle (negative weights dropped, the rest
// renormalised; the centroid when none is left).
void ClampIntoTriangle(std::array<double, 3>* bary) {
  double sum = 0.0;
  for (double& w : *bary) {
    w = std::max(0.0, w);
    sum += w;
  }
  for (double& w : *bary) w = sum > 0.0 ? w / sum : 1.0 / 3.0;
}

class Simplifier {
 public:
  Simplifier(const Mesh& mesh, const TriangleBvh& bvh, const std::vector<uint8_t>& is_boundary,
             const BaseDomainOptions& options);
  void Run(size_t target, const ProgressFn& progress);
  void RaiseValenceThree();
  BaseDomain Extract() const;

 private:
  void InitLoops(const MeshTopology& topology);
  void InitErrorBounds(const MeshTopology& topology, const BaseDomainOptions& options);
  bool BuildRing(uint32_t v, Ring* ring) const;
  // Sorted, without repeats, into *out (storage reused).
  void Neighbours(uint32_t v, std::vector<uint32_t>* out) const;
  // Collapse targets of v by cost. With `exact` false only the first cost is
  // exact and the others are lower bounds above it (enough to rank the queue).
  // Writes them to *out (its old contents dropped, its storage reused).
  void Candidates(uint32_t v, const Ring& ring, bool exact, CostScratch* scratch,
                  std::vector<std::pair<double, uint32_t>>* out) const;
  void EnqueueAll();
  // Cost of collapsing the star's centre into ring vertex p; reads the star's
  // input vertices from the scratch Candidates filled.
  // Stops early, returning a lower bound, once the cost exceeds `bound`.
  // worst_quality: of the fan's triangles (the caller ranks candidates by it).
  double CollapseCost(size_t p, const Ring& ring, double worst_quality, double bound,
                      CostScratch* scratch) const;
  // Re-queues the vertices of a changed ring with fresh costs, computed on the
  // team (the pushes stay in ring order, so the queue does not depend on it).
  void EnqueueRing(const std::vector<uint32_t>& verts);

  bool TryCollapse(uint32_t v, uint32_t u, const Ring& ring);
  struct Flip;
  bool FlipValid(const Flip& flip, double* error) const;
  void ApplyFlip(const Flip& flip);
  uint32_t FaceAcross(uint32_t f, uint32_t a, uint32_t b) const;
  Vec2 ChartPoint(const Flip& flip, uint32_t f, const ParamPoint& pp) const;
  Vec3 FlippedImage(const Flip& flip, size_t side, const Vec2& q) const;
  double AngleSum(uint32_t v) const;
  bool TopologyAllows(uint32_t v, size_t p, const Ring& ring) const;
  bool GeometryAllows(uint32_t v, size_t p, const Ring& ring, const std::vector<Vec2>& z);
  bool FacesAwayFromInput(uint32_t corner, const Vec3& b, const Vec3& c) const;
  void Apply(uint32_t v, size_t p, const Ring& ring, const std::vector<Vec2>& z);
  void GatherStarItems(uint32_t v, const Ring& ring, const std::vector<Vec2>& z);
  void CollapseStarFaces(uint32_t v, uint32_t u, const Ring& ring);
  void PlaceStarItems(uint32_t v, const Ring& ring, const std::vector<Vec2>& z);
  Vec2 ChartOf(uint32_t corner, uint32_t v, const Ring& ring, const std::vector<Vec2>& z) const;
  bool PlaceOnEdge(uint32_t x, uint32_t w1, uint32_t w2, double s, const std::vector<uint32_t>& new_faces);
  bool PlaceBoundaryItem(uint32_t x, const Face& old_face, const Vec2& q, uint32_t v, const Ring& ring,
                         const std::vector<Vec2>& z, const std::vector<uint32_t>& new_faces);
  void PlaceInteriorItem(uint32_t x, const Vec2& q, uint32_t v, const Ring& ring, const std::vector<Vec2>& z,
                         const std::vector<uint32_t>& new_faces);

  const std::vector<Vec3>& pos_;
  const TriangleBvh& bvh_;
  std::vector<uint32_t> face_part_;    // FacePartsForFoldTest
  std::vector<uint32_t> vertex_part_;  // the part of each vertex (empty: one part)
  const Mesh& input_;
  const std::vector<uint8_t>& boundary_;
  std::vector<Face> faces_;
  std::vector<uint8_t> face_alive_;
  std::vector<std::vector<uint32_t>> vfaces_;
  std::vector<uint8_t> alive_;
  std::vector<uint32_t> stamp_;
  std::vector<std::vector<std::pair<double, uint32_t>>> candidates_;  // of the queued entry
  CostScratch scratch_;  // for the sequential evaluations
  // Buffers of TryCollapse and Apply (sequential), reused across collapses.
  struct CollapseScratch {
    std::vector<Vec3> ring_pos;
    std::vector<Vec2> z, chart;
    std::vector<uint32_t> items, new_faces;
    std::vector<ParamPoint> old_params;
    std::vector<Face> old_corners;
    std::vector<uint32_t> wedge_starts;  // GeometryAllows' wedges not at the target
    std::vector<uint8_t> away;           // and whether each faces away from the input
  };
  CollapseScratch collapse_;
  // Run's team while it runs: EnqueueRing and GeometryAllows (via TryCollapse)
  // are only called from Run.
  SpinTeam* team_ = nullptr;
  std::vector<CostScratch> team_scratch_;  // one per team worker
  std::vector<Vec3> normal_;  // area-weighted input vertex normals
  // Squared bound on the distance between an input vertex and its image on the
  // base, per vertex (the bound of its component); infinite when unbounded.
  std::vector<double> max_error2_;
  std::vector<uint32_t> loop_of_;
  std::vector<size_t> loop_size_;
  std::vector<std::vector<uint32_t>> bucket_;  // removed input vertices mapped into each face
  std::vector<ParamPoint> params_;
  std::priority_queue<QueueEntry> queue_;
  size_t alive_count_ = 0;
};

Simplifier::Simplifier(const Mesh& mesh, const TriangleBvh& bvh, const std::vector<uint8_t>& is_boundary,
                       const BaseDomainOptions& options)
    : pos_(mesh.positions), bvh_(bvh), input_(mesh), boundary_(is_boundary), faces_(mesh.faces) {
  const size_t n = pos_.size();
  face_alive_.assign(faces_.size(), 1);
  vfaces_.resize(n);
  for (uint32_t f = 0; f < faces_.size(); ++f) {
    for (uint32_t c : faces_[f]) vfaces_[c].push_back(f);
  }
  alive_.assign(n, 1);
  alive_count_ = n;
  stamp_.assign(n, 0);
  candidates_.resize(n);
  bucket_.resize(faces_.size());
  params_.resize(n);
  normal_.assign(n, Vec3::Zero());
  for (const Face& f : faces_) {
    const Vec3 a = (pos_[f[1]] - pos_[f[0]]).cross(pos_[f[2]] - pos_[f[0]]);
    for (uint32_t c : f) normal_[c] += a;
  }
  const MeshTopology topology(mesh);
  InitLoops(topology);
  InitErrorBounds(topology, options);
  if (topology.num_components() > 1) {
    face_part_ = topology.FaceComponents();
    vertex_part_.assign(n, kAnyPart);
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      for (uint32_t c : faces_[f]) vertex_part_[c] = face_part_[f];
    }
  }
}

// Each component is bounded by its own diagonal, so a small part beside a large
// one (a bone of a skeleton) keeps its shape too.
void Simplifier::InitErrorBounds(const MeshTopology& topology, const BaseDomainOptions& options) {
  max_error2_.assign(pos_.size(), std::numeric_limits<double>::infinity());
  const double max_error_share = options.max_error_share;
  if (!(max_error_share > 0.0)) return;
  const std::vector<uint32_t>& face_component = topology.FaceComponents();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<BoundingBox> boxes(topology.num_components(), {Vec3::Constant(inf), Vec3::Constant(-inf)});
  for (size_t f = 0; f < faces_.size(); ++f) {
    BoundingBox& box = boxes[face_component[f]];
    for (uint32_t c : faces_[f]) {
      box.min = box.min.cwiseMin(pos_[c]);
      box.max = box.max.cwiseMax(pos_[c]);
    }
  }
  for (size_t f = 0; f < faces_.size(); ++f) {
    const double bound = max_error_share * boxes[face_component[f]].Diagonal();
    for (uint32_t c : faces_[f]) max_error2_[c] = bound * bound;
  }
  if (options.bound_scale.empty()) return;
  for (size_t v = 0; v < pos_.size(); ++v) {
    const double scale = options.bound_scale[v];
    max_error2_[v] *= scale * scale;
  }
}

void Simplifier::InitLoops(const MeshTopology& topology) {
  loop_of_.assign(pos_.size(), kNone);
  for (const BoundaryLoop& loop : topology.BoundaryLoops()) {
    for (uint32_t v : loop.vertices) loop_of_[v] = static_cast<uint32_t>(loop_size_.size());
    loop_size_.push_back(loop.vertices.size());
  }
}

bool Simplifier::BuildRing(uint32_t v, Ring* ring) const {
  const std::vector<uint32_t>& fs = vfaces_[v];
  const size_t nf = fs.size();
  if (nf == 0) return false;
  // Per thread: the team re-costs rings in parallel, and a fresh pair of
  // vectors per call would spend a tenth of the simplification's time in malloc/free.
  thread_local std::vector<uint32_t> from, to;
  from.resize(nf);
  to.resize(nf);
  for (size_t i = 0; i < nf; ++i) {
    const Face& f = faces_[fs[i]];
    const int c = f[0] == v ? 0 : (f[1] == v ? 1 : 2);
    from[i] = f[(c + 1) % 3];
    to[i] = f[(c + 2) % 3];
  }
  // Start at a wedge whose first vertex ends no other wedge (boundary), else anywhere.
  size_t start = 0;
  for (size_t i = 0; i < nf; ++i) {
    if (std::find(to.begin(), to.end(), from[i]) == to.end()) {
      start = i;
      break;
    }
  }
  ring->verts.clear();
  ring->faces.clear();
  size_t cur = start;
  for (size_t step = 0; step < nf; ++step) {
    ring->verts.push_back(from[cur]);
    ring->faces.push_back(fs[cur]);
    const uint32_t next_vertex = to[cur];
    if (step + 1 == nf) {
      ring->closed = next_vertex == ring->verts.front();
      if (!ring->closed) ring->verts.push_back(next_vertex);
      break;
    }
    const auto it = std::find(from.begin(), from.end(), next_vertex);
    if (it == from.end()) return false;  // fan broken: not a single manifold fan
    cur = static_cast<size_t>(it - from.begin());
  }
  return ring->closed == !boundary_[v];
}

void Simplifier::Neighbours(uint32_t v, std::vector<uint32_t>* out) const {
  std::vector<uint32_t>& n = *out;
  n.clear();
  for (uint32_t f : vfaces_[v]) {
    for (uint32_t c : faces_[f]) {
      if (c != v) n.push_back(c);
    }
  }
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
}

// Collapse cost (departure from MAPS's area + curvature weights and from QEM):
// the largest squared distance between an input vertex mapped into v's star (v
// included) and its image on the fan around u after the collapse, i.e. the
// error the base map itself would make there, divided by the worst new fan
// triangle's quality cubed. Quadric error sums over area, so it removes small
// protrusions (claws, ear tips) early and the remesh can never get them back;
// the largest distance keeps them until they are the coarsest detail left. The
// quality term keeps base triangles from becoming slivers along cylinders, where
// the dyadic subdivision of an equilateral reference triangle would sample the
// surface anisotropically. The power 3 gives fewer folds and more normal vertices
// than 2 on the bench meshes; error alone leaves slivers along ears and legs.
double Simplifier::CollapseCost(size_t p, const Ring& ring, double worst_quality, double bound,
                                CostScratch* scratch) const {
  const std::vector<Vec2>& z = scratch->z;
  const size_t d = ring.verts.size();
  const size_t wedges = ring.closed ? d : d - 1;
  const Vec3& pu = pos_[ring.verts[p]];
  std::vector<FanTriangle>& fan = scratch->fan;
  fan.clear();
  for (size_t m = 0; m < wedges; ++m) {
    const size_t m1 = (m + 1) % d;
    if (m == p || m1 == p) continue;
    Eigen::Matrix2d e;
    e.col(0) = z[m] - z[p];
    e.col(1) = z[m1] - z[p];
    if (!(std::abs(e.determinant()) > 1e-300)) continue;
    const Vec3& pa = pos_[ring.verts[m]];
    const Vec3& pb = pos_[ring.verts[m1]];
    fan.push_back({e.inverse(), pa - pu, pb - pu});
  }
  const std::vector<Vec2>& chart = scratch->chart;
  const std::vector<Vec3>& items = scratch->items;
  const std::vector<Vec3>& normals = scratch->normals;
  std::vector<Vec3>& facing = scratch->facing;
  facing.assign(fan.size(), Vec3::Zero());
  const double q = std::max(worst_quality, kQualityFloor);
  const double scale = 1.0 / (q * q * q);
  const double max_error2 = max_error2_[scratch->centre];
  const double worst_bound = std::min(bound / scale, max_error2);
  double worst = 0.0;
  for (size_t i = 0; i < items.size(); ++i) {
    const Vec2 rel = chart[i] - z[p];
    double best = -1e300;
    Vec3 offset = Vec3::Zero();
    size_t home = 0;
    for (size_t ti = 0; ti < fan.size(); ++ti) {
      const FanTriangle& t = fan[ti];
      const Vec2 w = t.to_weights * rel;
      const double inside = std::min({1.0 - w[0] - w[1], w[0], w[1]});
      if (inside <= best) continue;
      best = inside;
      home = ti;
      const Vec2 c = w.cwiseMax(0.0);
      const double s = std::max(1.0, c.sum());
      offset = (c[0] / s) * t.to_a + (c[1] / s) * t.to_b;
      if (inside >= 0.0) break;
    }
    if (!fan.empty()) facing[home] += normals[i];
    worst = std::max(worst, (pu + offset - items[i]).squaredNorm());
    if (worst > worst_bound) break;  // refused, or costlier than the bound: a lower bound is enough
  }
  if (worst > max_error2) return kRefusedCost;
  // A fan triangle that faces away from the input vertices it would carry folds
  // the base; every remesh level below it would inherit the fold.
  for (size_t ti = 0; ti < fan.size(); ++ti) {
    if (fan[ti].to_a.cross(fan[ti].to_b).dot(facing[ti]) < 0.0) return kRefusedCost;
  }
  return worst * scale;
}

void Simplifier::Candidates(uint32_t v, const Ring& ring, bool exact, CostScratch* scratch,
                            std::vector<std::pair<double, uint32_t>>* out_ptr) const {
  std::vector<std::pair<double, uint32_t>>& out = *out_ptr;
  out.clear();
  scratch->centre = v;
  std::vector<Vec3>& ring_pos = scratch->ring_pos;
  ring_pos.clear();
  for (uint32_t k : ring.verts) ring_pos.push_back(pos_[k]);
  std::vector<Vec2>& z = scratch->z;
  if (!FlattenRing(pos_[v], ring_pos, ring.closed, &z)) return;
  // Chart position and 3D position of every input vertex mapped into the star.
  std::vector<Vec2>& chart = scratch->chart;
  std::vector<Vec3>& items = scratch->items;
  std::vector<Vec3>& normals = scratch->normals;
  // v first: it moves the most, so its error is usually the largest and the
  // early exit of CollapseCost comes soonest.
  chart.assign(1, Vec2::Zero());
  items.assign(1, pos_[v]);
  normals.assign(1, normal_[v]);
  const size_t d = ring.verts.size();
  for (size_t m = 0; m < ring.faces.size(); ++m) {
    // faces[m] = (v, k_m, k_{m+1}) up to rotation.
    const Face& t = faces_[ring.faces[m]];
    const uint32_t km = ring.verts[m];
    const Vec2& zm = z[m];
    const Vec2& zm1 = z[(m + 1) % d];
    auto corner = [&](uint32_t c) { return c == v ? Vec2(Vec2::Zero()) : (c == km ? zm : zm1); };
    const Vec2 c0 = corner(t[0]), c1 = corner(t[1]), c2 = corner(t[2]);
    for (uint32_t x : bucket_[ring.faces[m]]) {
      const std::array<double, 3>& b = params_[x].bary;
      chart.push_back(b[0] * c0 + b[1] * c1 + b[2] * c2);
      items.push_back(pos_[x]);
      normals.push_back(normal_[x]);
    }
  }
  const size_t wedges = ring.closed ? d : d - 1;
  // Best-shaped fans first: their cost is usually the lowest, which makes the
  // early-exit bound of the others tight.
  std::vector<std::pair<double, size_t>>& order = scratch->order;
  order.clear();
  for (size_t p = 0; p < d; ++p) {
    // Boundary vertices collapse only along their boundary.
    if (boundary_[v] && p != 0 && p + 1 != d) continue;
    double worst = 1.0;
    for (size_t m = 0; m < wedges; ++m) {
      const size_t m1 = (m + 1) % d;
      if (m == p || m1 == p) continue;
      worst = std::min(worst, TriangleQuality(pos_[ring.verts[p]], pos_[ring.verts[m]], pos_[ring.verts[m1]]));
    }
    order.push_back({-worst, p});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [neg_quality, p] : order) {
    const double bound = exact || out.empty() ? 1e300 : out.front().first;
    const double cost = CollapseCost(p, ring, -neg_quality, bound, scratch);
    if (cost == kRefusedCost) continue;
    out.push_back({cost, ring.verts[p]});
    if (cost < out.front().first) std::swap(out.front(), out.back());
  }
  std::sort(out.begin(), out.end());
}

// Every vertex's first evaluation is independent of the others: computed in
// parallel (per-thread scratch), queued in vertex order.
void Simplifier::EnqueueAll() {
  ParallelFor(pos_.size(), [&](size_t begin, size_t end, size_t) {
    CostScratch scratch;
    for (size_t v = begin; v < end; ++v) {
      if (alive_[v] && BuildRing(static_cast<uint32_t>(v), &scratch.ring)) {
        Candidates(static_cast<uint32_t>(v), scratch.ring, false, &scratch, &candidates_[v]);
      }
    }
  });
  for (uint32_t v = 0; v < pos_.size(); ++v) {
    if (!candidates_[v].empty()) queue_.push({candidates_[v].front().first, v, stamp_[v]});
  }
}

void Simplifier::EnqueueRing(const std::vector<uint32_t>& verts) {
  for (uint32_t w : verts) {
    ++stamp_[w];
    candidates_[w].clear();
  }
  team_->Run(verts.size(), [&](size_t i, int worker) {
    const uint32_t w = verts[i];
    CostScratch& scratch = team_scratch_[static_cast<size_t>(worker)];
    if (!alive_[w] || !BuildRing(w, &scratch.ring)) return;
    Candidates(w, scratch.ring, false, &scratch, &candidates_[w]);
  });
  for (uint32_t w : verts) {
    if (!candidates_[w].empty()) queue_.push({candidates_[w].front().first, w, stamp_[w]});
  }
}

bool Simplifier::TopologyAllows(uint32_t v, size_t p, const Ring& ring) const {
  const size_t d = ring.verts.size();
  const uint32_t u = ring.verts[p];
  if (boundary_[v]) {
    if (ring.closed || (p != 0 && p + 1 != d) || d < 3) return false;
    if (loop_of_[v] == kNone || loop_size_[loop_of_[v]] < 4) return false;
  } else if (!ring.closed || d < 3) {
    return false;
  }
  // Link condition: u and v share exactly the apexes of the faces on edge (u, v).
  std::vector<uint32_t> opposite;
  if (ring.closed) {
    opposite = {ring.verts[(p + d - 1) % d], ring.verts[(p + 1) % d]};
  } else {
    opposite = {ring.verts[p == 0 ? 1 : d - 2]};
  }
  thread_local std::vector<uint32_t> nu;  // TopologyAllows runs once per collapse tried
  Neighbours(u, &nu);
  size_t common = 0;
  for (uint32_t k : ring.verts) {
    if (k != u && std::binary_search(nu.begin(), nu.end(), k)) ++common;
  }
  if (common != opposite.size()) return false;
  // Apexes lose a neighbour: interior ones must keep 3, boundary ones 2.
  for (uint32_t w : opposite) {
    const size_t neighbours = vfaces_[w].size() + (boundary_[w] ? 1 : 0);
    if (neighbours - 1 < (boundary_[w] ? 2u : 3u)) return false;
  }
  const size_t new_valence = (nu.size() - 1) + (d - 1) - common;
  return new_valence <= kMaxValence + (boundary_[u] ? 1 : 0);
}

bool Simplifier::GeometryAllows(uint32_t v, size_t p, const Ring& ring, const std::vector<Vec2>& z) {
  const size_t d = ring.verts.size();
  const uint32_t u = ring.verts[p];
  const size_t wedges = ring.closed ? d : d - 1;
  double worst_old = 1.0;
  for (size_t m = 0; m < wedges; ++m) {
    const Vec3& a = pos_[ring.verts[m]];
    const Vec3& b = pos_[ring.verts[(m + 1) % d]];
    worst_old = std::min(worst_old, TriangleQuality(pos_[v], a, b));
  }
  for (size_t m = 0; m < wedges; ++m) {
    const size_t m1 = (m + 1) % d;
    if (ring.verts[m] == u || ring.verts[m1] == u) continue;
    if (!(Orient2d(z[p], z[m], z[m1]) > 1e-12)) return false;
    const Vec3& a = pos_[ring.verts[m]];
    const Vec3& b = pos_[ring.verts[m1]];
    const Vec3 n_old = (a - pos_[v]).cross(b - pos_[v]);
    const Vec3 n_new = (a - pos_[u]).cross(b - pos_[u]);
    const double ln = n_new.norm(), lo = n_old.norm();
    if (!(ln > 0.0)) return false;
    if (lo > 0.0 && n_old.dot(n_new) < kMinNormalCos * lo * ln) return false;
    const double q = TriangleQuality(pos_[u], a, b);
    if (q < kMinQuality && q < worst_old) return false;
  }
  // Last, once every cheap test passed: a closest-point query per wedge, on the
  // team (on the caller alone it is a fifth of the simplification's time, igea).
  std::vector<uint32_t>& wedge_starts = collapse_.wedge_starts;
  wedge_starts.clear();
  for (size_t m = 0; m < wedges; ++m) {
    if (ring.verts[m] != u && ring.verts[(m + 1) % d] != u) wedge_starts.push_back(static_cast<uint32_t>(m));
  }
  std::vector<uint8_t>& away = collapse_.away;
  away.assign(wedge_starts.size(), 0);
  const auto test = [&](size_t i, int) {
    const size_t m = wedge_starts[i];
    away[i] = FacesAwayFromInput(u, pos_[ring.verts[m]], pos_[ring.verts[(m + 1) % d]]) ? 1 : 0;
  };
  team_->Run(wedge_starts.size(), test);
  return std::none_of(away.begin(), away.end(), [](uint8_t a) { return a != 0; });
}

// The remesh's fold test (quality_checks.h) on the base triangle (corner, b, c),
// against the input part `corner` belongs to: it faces away from it at the
// closest point of its centroid. A folded base face seeds folds and
// unconverged patches at every level below it.
bool Simplifier::FacesAwayFromInput(uint32_t corner, const Vec3& b, const Vec3& c) const {
  const uint32_t part = vertex_part_.empty() ? kAnyPart : vertex_part_[corner];
  return eqmesh::FacesAwayFromInput(bvh_, input_, face_part_, part, pos_[corner], b, c);
}

bool Simplifier::TryCollapse(uint32_t v, uint32_t u, const Ring& ring) {
  const auto it = std::find(ring.verts.begin(), ring.verts.end(), u);
  if (it == ring.verts.end()) return false;
  const size_t p = static_cast<size_t>(it - ring.verts.begin());
  if (!TopologyAllows(v, p, ring)) return false;
  std::vector<Vec3>& ring_pos = collapse_.ring_pos;
  ring_pos.clear();
  for (uint32_t k : ring.verts) ring_pos.push_back(pos_[k]);
  std::vector<Vec2>& z = collapse_.z;
  if (!FlattenRing(pos_[v], ring_pos, ring.closed, &z)) return false;
  if (!GeometryAllows(v, p, ring, z)) return false;
  Apply(v, p, ring, z);
  return true;
}

Vec2 Simplifier::ChartOf(uint32_t corner, uint32_t v, const Ring& ring, const std::vector<Vec2>& z) const {
  if (corner == v) return Vec2::Zero();
  for (size_t m = 0; m < ring.verts.size(); ++m) {
    if (ring.verts[m] == corner) return z[m];
  }
  return Vec2::Zero();  // unreachable for faces of the star
}

// Input boundary vertices stay exactly on a boundary edge: find the edge they lie
// on after the collapse and write exact barycentrics (one coordinate zero).
bool Simplifier::PlaceBoundaryItem(uint32_t x, const Face& of, const Vec2& q, uint32_t v, const Ring& ring,
                                   const std::vector<Vec2>& z, const std::vector<uint32_t>& new_faces) {
  const ParamPoint old = params_[x];
  int zero = 0;
  for (int i = 1; i < 3; ++i) {
    if (old.bary[i] < old.bary[zero]) zero = i;
  }
  uint32_t w1 = of[(zero + 1) % 3], w2 = of[(zero + 2) % 3];
  double s = old.bary[(zero + 2) % 3] / std::max(1e-300, old.bary[(zero + 1) % 3] + old.bary[(zero + 2) % 3]);
  if (w1 == v || w2 == v) {
    if (ring.closed) return false;
    const size_t d = ring.verts.size();
    w1 = ring.verts[0];
    w2 = ring.verts[d - 1];
    const double span = z[d - 1].x() - z[0].x();
    if (!(std::abs(span) > 0.0)) return false;
    s = std::clamp((q.x() - z[0].x()) / span, 0.0, 1.0);
  }
  return PlaceOnEdge(x, w1, w2, s, new_faces);
}

bool Simplifier::PlaceOnEdge(uint32_t x, uint32_t w1, uint32_t w2, double s,
                             const std::vector<uint32_t>& new_faces) {
  for (uint32_t f : new_faces) {
    const Face& nf = faces_[f];  // post-collapse corners
    for (int i = 0; i < 3; ++i) {
      if (nf[i] == w1 && nf[(i + 1) % 3] == w2) {
        ParamPoint pp{f, {0, 0, 0}};
        pp.bary[i] = 1.0 - s;
        pp.bary[(i + 1) % 3] = s;
        params_[x] = pp;
        return true;
      }
      if (nf[i] == w2 && nf[(i + 1) % 3] == w1) {
        ParamPoint pp{f, {0, 0, 0}};
        pp.bary[i] = s;
        pp.bary[(i + 1) % 3] = 1.0 - s;
        params_[x] = pp;
        return true;
      }
    }
  }
  return false;
}

void Simplifier::PlaceInteriorItem(uint32_t x, const Vec2& q, uint32_t v, const Ring& ring,
                                   const std::vector<Vec2>& z, const std::vector<uint32_t>& new_faces) {
  double best = -1e300;
  ParamPoint best_pp;
  for (uint32_t f : new_faces) {
    const Face& nf = faces_[f];
    Eigen::Vector3d b;
    if (!Barycentric2d(q, ChartOf(nf[0], v, ring, z), ChartOf(nf[1], v, ring, z), ChartOf(nf[2], v, ring, z), &b)) {
      continue;
    }
    const double worst = b.minCoeff();
    if (worst > best) {
      best = worst;
      best_pp.face = f;
      best_pp.bary = {b[0], b[1], b[2]};
    }
  }
  ClampIntoTriangle(&best_pp.bary);
  params_[x] = best_pp;
}

// Phase 1 of a collapse: the chart position of every input vertex mapped into v's
// star (and of v itself), taken while the star's faces are still the old ones.
void Simplifier::GatherStarItems(uint32_t v, const Ring& ring, const std::vector<Vec2>& z) {
  std::vector<uint32_t>& items = collapse_.items;
  std::vector<Vec2>& chart = collapse_.chart;
  items.clear();
  chart.clear();
  for (uint32_t f : ring.faces) {
    for (uint32_t x : bucket_[f]) {
      const Face& t = faces_[f];
      Vec2 q = Vec2::Zero();
      for (int i = 0; i < 3; ++i) q += params_[x].bary[i] * ChartOf(t[i], v, ring, z);
      items.push_back(x);
      chart.push_back(q);
    }
    bucket_[f].clear();
  }
  items.push_back(v);
  chart.push_back(Vec2::Zero());
  // Boundary items need their pre-collapse face; remember those.
  collapse_.old_params.clear();
  for (uint32_t x : items) collapse_.old_params.push_back(params_[x]);
}

// Phase 2: retriangulate the star: faces with u die, the others get u in place of
// v; v leaves the mesh.
void Simplifier::CollapseStarFaces(uint32_t v, uint32_t u, const Ring& ring) {
  std::vector<uint32_t>& new_faces = collapse_.new_faces;
  std::vector<Face>& old_corners = collapse_.old_corners;
  new_faces.clear();
  old_corners.clear();
  for (uint32_t f : ring.faces) old_corners.push_back(faces_[f]);
  for (uint32_t f : ring.faces) {
    Face& t = faces_[f];
    if (t[0] == u || t[1] == u || t[2] == u) {
      face_alive_[f] = 0;
      for (uint32_t c : t) {
        if (c == v) continue;
        auto& list = vfaces_[c];
        list.erase(std::remove(list.begin(), list.end(), f), list.end());
      }
    } else {
      for (uint32_t& c : t) {
        if (c == v) c = u;
      }
      vfaces_[u].push_back(f);
      new_faces.push_back(f);
    }
  }
  vfaces_[v].clear();
  alive_[v] = 0;
  --alive_count_;
  if (boundary_[v]) --loop_size_[loop_of_[v]];
}

// Phase 3: every gathered item gets a parameter on the new faces (boundary items
// on the boundary edges, v on the chord between its boundary neighbours).
void Simplifier::PlaceStarItems(uint32_t v, const Ring& ring, const std::vector<Vec2>& z) {
  const std::vector<uint32_t>& items = collapse_.items;
  const std::vector<uint32_t>& new_faces = collapse_.new_faces;
  for (size_t i = 0; i < items.size(); ++i) {
    const uint32_t x = items[i];
    bool placed = false;
    if (boundary_[x] && x != v) {
      const size_t k = static_cast<size_t>(
          std::find(ring.faces.begin(), ring.faces.end(), collapse_.old_params[i].face) - ring.faces.begin());
      placed = PlaceBoundaryItem(x, collapse_.old_corners[k], collapse_.chart[i], v, ring, z, new_faces);
    } else if (x == v && boundary_[v]) {
      const size_t d = ring.verts.size();
      const double span = z[d - 1].x() - z[0].x();
      const double s = std::abs(span) > 0.0 ? std::clamp(-z[0].x() / span, 0.0, 1.0) : 0.5;
      placed = PlaceOnEdge(x, ring.verts[0], ring.verts[d - 1], s, new_faces);
    }
    if (!placed) PlaceInteriorItem(x, collapse_.chart[i], v, ring, z, new_faces);
    bucket_[params_[x].face].push_back(x);
  }
}

void Simplifier::Apply(uint32_t v, size_t p, const Ring& ring, const std::vector<Vec2>& z) {
  GatherStarItems(v, ring, z);
  CollapseStarFaces(v, ring.verts[p], ring);
  PlaceStarItems(v, ring, z);
}

void Simplifier::Run(size_t target, const ProgressFn& progress) {
  EnqueueAll();
  SpinTeam team(std::min(WorkerThreadLimit(), kTeamWorkers));
  team_scratch_.resize(static_cast<size_t>(team.workers()));
  team_ = &team;
  const size_t start = alive_count_;
  size_t reported = 0;
  Ring ring;
  std::vector<std::pair<double, uint32_t>> cands;
  while (alive_count_ > target && !queue_.empty()) {
    const QueueEntry e = queue_.top();
    queue_.pop();
    const uint32_t v = e.vertex;
    if (!alive_[v] || e.stamp != stamp_[v] || !BuildRing(v, &ring)) continue;
    bool done = false;
    cands.clear();
    cands.swap(candidates_[v]);  // its storage goes back for the next re-costing
    for (size_t c = 0; c < cands.size(); ++c) {
      // The queue ranked v by its cheapest target alone; when that one is
      // refused, rank the others exactly before trying them.
      if (c == 1) {
        Candidates(v, ring, true, &scratch_, &cands);
        if (cands.size() < 2) break;
      }
      const auto& cand = cands[c];
      if (TryCollapse(v, cand.second, ring)) {
        // Only the stars of v's ring changed (their faces and buckets); every
        // other vertex keeps its cost.
        EnqueueRing(ring.verts);
        done = true;
        break;
      }
    }
    if (!done) ++stamp_[v];  // stuck until a collapse nearby changes its star
    const size_t removed = start - alive_count_;
    if (progress && removed >= reported + start / 100 + 1) {
      reported = removed;
      ReportProgress(progress, "base domain", static_cast<double>(removed) / static_cast<double>(start - std::min(start, target) + 1));
    }
  }
  team_ = nullptr;
}

// An edge flip of the base mesh (a, b) -> (v, x): faces f1 = (v, a, b) and
// f2 = (x, b, a), up to rotation, become (v, a, x) and (v, x, b). The chart
// unfolds the quad about (a, b): a at the origin, b on +x, v above, x below.
struct Simplifier::Flip {
  uint32_t f1, f2, v, a, b, x;
  Vec2 cv, cb, cx;  // chart positions of v, b, x (a is the origin)
};

uint32_t Simplifier::FaceAcross(uint32_t f, uint32_t a, uint32_t b) const {
  for (uint32_t g : vfaces_[a]) {
    if (g == f) continue;
    const Face& t = faces_[g];
    if (t[0] == b || t[1] == b || t[2] == b) return g;
  }
  return kNone;
}

namespace {

// Where p lands when the triangle (origin, (len, 0), p) is unfolded about the
// segment from a to b: above the axis when `above`.
Vec2 Unfold(const Vec3& a, const Vec3& b, const Vec3& p, bool above) {
  const double len = (b - a).norm();
  const double da = (p - a).squaredNorm(), db = (p - b).squaredNorm();
  const double x = (da - db + len * len) / (2.0 * len);
  const double y = std::sqrt(std::max(0.0, da - x * x));
  return {x, above ? y : -y};
}

}  // namespace

// The flip unfolds to a convex quad, the new faces neither turn over nor face
// away from the input or from the input vertices they will carry, their quality
// is at least kMinQuality, and those input vertices stay within the error
// bound. *error: the largest squared distance of those input vertices to their
// images on the new faces.
bool Simplifier::FlipValid(const Flip& k, double* error) const {
  const Vec2 ca = Vec2::Zero();
  if (!(Orient2d(k.cv, ca, k.cx) > 0.0) || !(Orient2d(k.cv, k.cx, k.cb) > 0.0)) return false;
  const Vec3 &pv = pos_[k.v], &pa = pos_[k.a], &pb = pos_[k.b], &px = pos_[k.x];
  const Vec3 n_old = (pa - pv).cross(pb - pv) + (pb - px).cross(pa - px);
  const std::array<std::array<uint32_t, 3>, 2> next = {{{k.v, k.a, k.x}, {k.v, k.x, k.b}}};
  std::array<Vec3, 2> facing = {Vec3::Zero(), Vec3::Zero()};
  double error_after = 0.0;
  for (uint32_t f : {k.f1, k.f2}) {
    for (uint32_t item : bucket_[f]) {
      const ParamPoint& pp = params_[item];
      const Vec2 q = ChartPoint(k, f, pp);
      // Left of v -> x lies b's side: new face 1, (v, x, b).
      const size_t side = Orient2d(k.cv, k.cx, q) > 0.0 ? 1 : 0;
      facing[side] += normal_[item];
      error_after = std::max(error_after, (FlippedImage(k, side, q) - pos_[item]).squaredNorm());
    }
  }
  double worst = 1.0;
  for (size_t i = 0; i < 2; ++i) {
    const Vec3 &p0 = pos_[next[i][0]], &p1 = pos_[next[i][1]], &p2 = pos_[next[i][2]];
    const Vec3 n = (p1 - p0).cross(p2 - p0);
    if (n.dot(n_old) < kMinNormalCos * n.norm() * n_old.norm()) return false;
    if (n.dot(facing[i]) < 0.0 || FacesAwayFromInput(next[i][0], p1, p2)) return false;
    worst = std::min(worst, TriangleQuality(p0, p1, p2));
  }
  *error = error_after;
  return worst >= kMinQuality && error_after <= max_error2_[k.v];
}

// The 3D image of chart point q on new face `side` of the flip (0: (v, a, x), 1: (v, x, b)).
Vec3 Simplifier::FlippedImage(const Flip& k, size_t side, const Vec2& q) const {
  Eigen::Vector3d w(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
  const uint32_t c1 = side == 0 ? k.a : k.x, c2 = side == 0 ? k.x : k.b;
  const Vec2 z1 = side == 0 ? Vec2(Vec2::Zero()) : k.cx, z2 = side == 0 ? k.cx : k.cb;
  Barycentric2d(q, k.cv, z1, z2, &w);
  return w[0] * pos_[k.v] + w[1] * pos_[c1] + w[2] * pos_[c2];
}

Vec2 Simplifier::ChartPoint(const Flip& k, uint32_t f, const ParamPoint& pp) const {
  Vec2 q = Vec2::Zero();
  for (int i = 0; i < 3; ++i) {
    const uint32_t w = faces_[f][static_cast<size_t>(i)];
    const Vec2 c = w == k.v ? k.cv : w == k.b ? k.cb : w == k.x ? k.cx : Vec2(Vec2::Zero());
    q += pp.bary[static_cast<size_t>(i)] * c;
  }
  return q;
}

void Simplifier::ApplyFlip(const Flip& k) {
  std::vector<uint32_t> items = bucket_[k.f1];
  items.insert(items.end(), bucket_[k.f2].begin(), bucket_[k.f2].end());
  std::vector<Vec2> chart;
  for (uint32_t item : items) {
    chart.push_back(ChartPoint(k, params_[item].face, params_[item]));
  }
  faces_[k.f1] = {k.v, k.a, k.x};
  faces_[k.f2] = {k.v, k.x, k.b};
  auto drop = [&](uint32_t w, uint32_t f) {
    auto& list = vfaces_[w];
    list.erase(std::remove(list.begin(), list.end(), f), list.end());
  };
  drop(k.a, k.f2);
  drop(k.b, k.f1);
  vfaces_[k.v].push_back(k.f2);
  vfaces_[k.x].push_back(k.f1);
  bucket_[k.f1].clear();
  bucket_[k.f2].clear();
  const std::array<std::array<Vec2, 3>, 2> corners = {{{k.cv, Vec2::Zero(), k.cx}, {k.cv, k.cx, k.cb}}};
  for (size_t i = 0; i < items.size(); ++i) {
    double best = -1e300;
    ParamPoint best_pp;
    for (size_t n = 0; n < 2; ++n) {
      Eigen::Vector3d w;
      if (!Barycentric2d(chart[i], corners[n][0], corners[n][1], corners[n][2], &w)) continue;
      if (w.minCoeff() > best) {
        best = w.minCoeff();
        best_pp = {n == 0 ? k.f1 : k.f2, {w[0], w[1], w[2]}};
      }
    }
    ClampIntoTriangle(&best_pp.bary);
    params_[items[i]] = best_pp;
    bucket_[best_pp.face].push_back(items[i]);
  }
}

// The corner angles of v's faces at v, summed (2 pi where the base is flat).
double Simplifier::AngleSum(uint32_t v) const {
  double angles = 0.0;
  for (uint32_t f : vfaces_[v]) {
    const Face& t = faces_[f];
    const size_t c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const Vec3& a = pos_[t[(c + 1) % 3]];
    const Vec3& b = pos_[t[(c + 2) % 3]];
    if (!((a - pos_[v]).norm() > 0.0 && (b - pos_[v]).norm() > 0.0)) return 2.0 * kPi;  // degenerate: no tip to speak of
    angles += CornerAngle(pos_[v], a, b);
  }
  return angles;
}

// Interior base vertices of valence 3 stay extraordinary at every level with
// three wide finest faces around them; at tips (claws, ear tips) one of those
// folds and no move unfolds it (all of armadillo's and skull's folds, and the
// horse's ear pleat, traced back to one). Collapsing them loses the tip
// (armadillo: 70 dB instead of 86), so instead an edge opposite a tip
// (kTipAngleSum) is flipped when that is valid (FlipValid) and leaves no interior
// vertex below valence 4: of the valid ones, the one whose new faces carry their
// input vertices closest. Every flip moves the remesh a little, and not always for
// the better (flat vertices fold, CAD corners lose a few dB), hence the tip
// limit; 300 degrees keeps the fewest folds on the fold suite (measured:
// bench/log/2026-12-05-remesh-notebook.md).
// Departure from MAPS, which has no flips. Boundary neighbourhoods are left
// alone (their input vertices sit exactly on base boundary edges).
void Simplifier::RaiseValenceThree() {
  for (uint32_t v = 0; v < pos_.size(); ++v) {
    if (!alive_[v] || boundary_[v] || vfaces_[v].size() != 3) continue;
    if (AngleSum(v) >= kTipAngleSum) continue;
    std::optional<Flip> best;
    double best_error = std::numeric_limits<double>::infinity();
    std::vector<uint32_t> nv;
    Neighbours(v, &nv);
    for (uint32_t f1 : vfaces_[v]) {
      const Face& t = faces_[f1];
      const size_t c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      Flip k{f1, kNone, v, t[(c + 1) % 3], t[(c + 2) % 3], kNone, {}, {}, {}};
      k.f2 = FaceAcross(f1, k.a, k.b);
      if (k.f2 == kNone) continue;
      for (uint32_t w : faces_[k.f2]) {
        if (w != k.a && w != k.b) k.x = w;
      }
      if (k.x == kNone || boundary_[k.a] || boundary_[k.b] || boundary_[k.x]) continue;
      if (vfaces_[k.a].size() < 5 || vfaces_[k.b].size() < 5 || vfaces_[k.x].size() >= kMaxValence) continue;
      if (std::binary_search(nv.begin(), nv.end(), k.x)) continue;
      const Vec3& pa = pos_[k.a];
      const Vec3& pb = pos_[k.b];
      if (!((pb - pa).norm() > 0.0)) continue;
      k.cv = Unfold(pa, pb, pos_[v], true);
      k.cb = Vec2((pb - pa).norm(), 0.0);
      k.cx = Unfold(pa, pb, pos_[k.x], false);
      double error = 0.0;
      if (FlipValid(k, &error) && error < best_error) {
        best_error = error;
        best = k;
      }
    }
    if (best) ApplyFlip(*best);
  }
}

BaseDomain Simplifier::Extract() const {
  BaseDomain out;
  std::vector<uint32_t> vmap(pos_.size(), kNone);
  for (uint32_t v = 0; v < pos_.size(); ++v) {
    if (alive_[v] && !vfaces_[v].empty()) {
      vmap[v] = static_cast<uint32_t>(out.base_to_input.size());
      out.base_to_input.push_back(v);
    }
  }
  std::vector<uint32_t> fmap(faces_.size(), kNone);
  for (uint32_t f = 0; f < faces_.size(); ++f) {
    if (!face_alive_[f]) continue;
    fmap[f] = static_cast<uint32_t>(out.faces.size());
    out.faces.push_back({vmap[faces_[f][0]], vmap[faces_[f][1]], vmap[faces_[f][2]]});
  }
  out.params.resize(pos_.size());
  for (uint32_t x = 0; x < pos_.size(); ++x) {
    if (alive_[x]) {
      const uint32_t f = vfaces_[x].front();
      ParamPoint pp{fmap[f], {0, 0, 0}};
      for (int i = 0; i < 3; ++i) pp.bary[i] = faces_[f][i] == x ? 1.0 : 0.0;
      out.params[x] = pp;
    } else {
      out.params[x] = {fmap[params_[x].face], params_[x].bary};
    }
  }
  return out;
}

}  // namespace

StatusOr<BaseDomain> BuildBaseDomain(const Mesh& mesh, const TriangleBvh& bvh,
                                     const std::vector<uint8_t>& is_boundary, const BaseDomainOptions& options) {
  if (mesh.faces.empty()) return InvalidMesh("no faces to simplify");
  if (is_boundary.size() != mesh.positions.size()) return InternalError("boundary flags size mismatch");
  if (!options.bound_scale.empty() && options.bound_scale.size() != mesh.positions.size()) {
    return InternalError("bound scale size mismatch");
  }
  Simplifier s(mesh, bvh, is_boundary, options);
  s.Run(options.target_vertices, options.progress);
  if (options.raise_valence_three) s.RaiseValenceThree();
  BaseDomain base = s.Extract();
  for (const ParamPoint& pp : base.params) {
    if (pp.face >= base.faces.size()) return InternalError("base domain lost an input vertex's parameter");
  }
  return base;
}

}  // namespace eqmesh

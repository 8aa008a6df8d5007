// TriangleBvh implementation.
//
// Build: binned SAH over triangle centroids (Wald, RT 2007), 12 bins on the
// widest centroid axis (Wald bins all three), leaves of at most 4 triangles, nodes in one flat array
// with sibling pairs adjacent. Departures: the build is iterative (an explicit
// task stack, so no recursion limit on hostile input), and below depth 40 we
// stop trusting the SAH and split at the centroid median, which bounds the
// tree depth by 40 + 32 and lets queries use a fixed-size stack.
//
// Closest point: Voronoi-region test of Ericson, Real-Time Collision
// Detection §5.1.5. Departure: nearly degenerate triangles (corner angle
// below ~1e-8 rad or a zero-length edge) are treated as their three edges,
// because the region test divides by quantities that vanish there.
//
// Rays: Möller & Trumbore (JGT 1997) in double precision. Departure: the
// barycentric range test is inclusive with a small epsilon so a ray through a
// shared edge or vertex is never lost between the two faces; the duplicate
// hits this creates are merged by t afterwards (RayAllHits).
#include "mesh/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>  // cross products

namespace eqmesh {
namespace {

constexpr uint32_t kMaxLeafSize = 4;
constexpr int kNumBins = 12;
constexpr int kSahMaxDepth = 40;
constexpr int kStackSize = 128;  // >= max depth (40 SAH + 32 median levels) + 2
// Barycentric slack for the inclusive ray test (dimensionless).
constexpr double kBaryEps = 1e-9;
// Hits closer than this fraction of the box diagonal along the ray are one hit.
constexpr double kMergeFraction = 1e-9;

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void Grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void Grow(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  double HalfArea() const {
    if (lo.x() > hi.x()) return 0.0;
    const Vec3 e = hi - lo;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }
};

// Per-triangle data needed only during the build.
struct BuildPrim {
  Box box;
  Vec3 centroid;
};

struct BuildTask {
  uint32_t node;
  uint32_t begin, end;
  int depth;
};

struct Split {
  int axis = -1;
  int bin = 0;  // prims whose centroid falls in a bin < this go left
};

double SquaredDistanceToBox(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

int BinOf(double c, double lo, double inv_width) {
  const int b = static_cast<int>((c - lo) * inv_width);
  return std::clamp(b, 0, kNumBins - 1);
}

// Best binned-SAH split of prims[begin, end); axis == -1
// when every centroid coincides.
Split FindSahSplit(const std::vector<BuildPrim>& prims, const std::vector<uint32_t>& order,
                   uint32_t begin, uint32_t end, const Box& centroid_box) {
  Split best;
  double best_cost = std::numeric_limits<double>::infinity();
  // Only the widest centroid axis is binned: a third of the build time for a
  // tree that answers closest-point queries within a few percent as fast.
  int widest = 0;
  (centroid_box.hi - centroid_box.lo).maxCoeff(&widest);
  for (int axis = widest; axis == widest; ++axis) {
    const double lo = centroid_box.lo[axis];
    const double extent = centroid_box.hi[axis] - lo;
    if (!(extent > 0.0)) continue;
    const double inv_width = kNumBins / extent;
    Box bin_box[kNumBins];
    uint32_t bin_count[kNumBins] = {};
    for (uint32_t i = begin; i < end; ++i) {
      const BuildPrim& prim = prims[order[i]];
      const int b = BinOf(prim.centroid[axis], lo, inv_width);
      bin_box[b].Grow(prim.box);
      ++bin_count[b];
    }
    // Sweep from the right to get suffix areas, then from the left.
    double right_area[kNumBins];
    uint32_t right_count[kNumBins];
    Box acc;
    uint32_t n = 0;
    for (int b = kNumBins - 1; b > 0; --b) {
      acc.Grow(bin_box[b]);
      n += bin_count[b];
      right_area[b] = acc.HalfArea();
      right_count[b] = n;
    }
    acc = Box();
    n = 0;
    for (int b = 1; b < kNumBins; ++b) {
      acc.Grow(bin_box[b - 1]);
      n += bin_count[b - 1];
      if (n == 0 || right_count[b] == 0) continue;
      const double cost = acc.HalfArea() * n + right_area[b] * right_count[b];
      if (cost < best_cost) {
        best_cost = cost;
        best.axis = axis;
        best.bin = b;
      }
    }
  }
  return best;
}

// Splits order[begin, end) in two non-empty halves; returns the middle index.
uint32_t Partition(const std::vector<BuildPrim>& prims, std::vector<uint32_t>* order,
                   const BuildTask& task, const Box& centroid_box) {
  Split split;
  if (task.depth < kSahMaxDepth) split = FindSahSplit(prims, *order, task.begin, task.end, centroid_box);
  if (split.axis >= 0) {
    const double inv_width =
        kNumBins / (centroid_box.hi[split.axis] - centroid_box.lo[split.axis]);
    // Partition by bin index (not by coordinate) so it agrees exactly with the binning.
    auto mid = std::partition(order->begin() + task.begin, order->begin() + task.end,
                              [&](uint32_t i) {
                                return BinOf(prims[i].centroid[split.axis],
                                             centroid_box.lo[split.axis], inv_width) < split.bin;
                              });
    const auto m = static_cast<uint32_t>(mid - order->begin());
    if (m > task.begin && m < task.end) return m;
  }
  // Median on the widest centroid axis: always halves the count.
  const Vec3 extent = centroid_box.hi - centroid_box.lo;
  int axis = 0;
  extent.maxCoeff(&axis);
  const uint32_t m = task.begin + (task.end - task.begin) / 2;
  std::nth_element(order->begin() + task.begin, order->begin() + m, order->begin() + task.end,
                   [&](uint32_t a, uint32_t b) {
                     return prims[a].centroid[axis] < prims[b].centroid[axis];
                   });
  return m;
}

Status ValidateForBvh(const Mesh& mesh) {
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces");
  if (mesh.faces.size() >= kNoFace) return ResourceLimit("mesh has too many faces for a BVH");
  return CheckIndicesAndCoordinates(mesh);
}

Vec3 ClosestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b, double* t_out) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  *t_out = t;
  return a + t * ab;
}

// Closest point on the union of the three edges: the right answer for a
// triangle whose interior has (numerically) no area.
Vec3 ClosestPointOnDegenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                              std::array<double, 3>* bary) {
  const Vec3* corners[3] = {&a, &b, &c};
  double best_d2 = std::numeric_limits<double>::infinity();
  Vec3 best = a;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    double t = 0.0;
    const Vec3 q = ClosestPointOnSegment(p, *corners[i], *corners[j], &t);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
      *bary = {0.0, 0.0, 0.0};
      (*bary)[i] = 1.0 - t;
      (*bary)[j] = t;
    }
  }
  return best;
}

}  // namespace

Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                            std::array<double, 3>* bary) {
  const Vec3 ab = b - a, ac = c - a;
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  // sin^2 of the angle at a below 1e-16: the region test below would divide
  // by ~0, and the triangle is a segment to within 1e-8 of its size anyway.
  if (!(ab.cross(ac).squaredNorm() > 1e-16 * ab2 * ac2)) return ClosestPointOnDegenerate(p, a, b, c, bary);

  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    *bary = {1.0, 0.0, 0.0};
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    *bary = {0.0, 1.0, 0.0};
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);  // d1 - d3 = |ab|^2 > 0
    *bary = {1.0 - v, v, 0.0};
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    *bary = {0.0, 0.0, 1.0};
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);  // d2 - d6 = |ac|^2 > 0
    *bary = {1.0 - w, 0.0, w};
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));  // denominator = |bc|^2 > 0
    *bary = {0.0, 1.0 - w, w};
    return b + w * (c - b);
  }
  const double inv = 1.0 / (va + vb + vc);  // = 1 / |ab x ac|^2
  const double v = vb * inv, w = vc * inv;
  *bary = {1.0 - v - w, v, w};
  return a + v * ab + w * ac;
}

StatusOr<TriangleBvh> TriangleBvh::Build(const Mesh& mesh) {
  EQMESH_RETURN_IF_ERROR(ValidateForBvh(mesh));
  const auto n = static_cast<uint32_t>(mesh.faces.size());
  std::vector<BuildPrim> prims(n);
  Box all;
  for (uint32_t f = 0; f < n; ++f) {
    BuildPrim& prim = prims[f];
    for (uint32_t v : mesh.faces[f]) prim.box.Grow(mesh.positions[v]);
    prim.centroid = 0.5 * (prim.box.lo + prim.box.hi);
    all.Grow(prim.box);
  }
  TriangleBvh bvh;
  bvh.scale_ = std::max((all.hi - all.lo).norm(), std::numeric_limits<double>::min());
  // Pad boxes so the epsilon-inclusive ray test is not undone by box culling.
  const double pad = 1e-9 * bvh.scale_;

  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  bvh.nodes_.reserve(2 * static_cast<size_t>(n));  // a binary tree with <= n leaves
  bvh.nodes_.push_back(Node{});
  std::vector<BuildTask> tasks = {{0, 0, n, 0}};
  while (!tasks.empty()) {
    const BuildTask task = tasks.back();
    tasks.pop_back();
    Box box, centroid_box;
    for (uint32_t i = task.begin; i < task.end; ++i) {
      box.Grow(prims[order[i]].box);
      centroid_box.Grow(prims[order[i]].centroid);
    }
    Node& node = bvh.nodes_[task.node];
    node.lo = box.lo - Vec3::Constant(pad);
    node.hi = box.hi + Vec3::Constant(pad);
    if (task.end - task.begin <= kMaxLeafSize) {
      node.first = task.begin;
      node.count = task.end - task.begin;
      continue;
    }
    const uint32_t mid = Partition(prims, &order, task, centroid_box);
    const auto left = static_cast<uint32_t>(bvh.nodes_.size());
    node.first = left;  // `node` is invalid after the push_backs below
    node.count = 0;
    bvh.nodes_.push_back(Node{});
    bvh.nodes_.push_back(Node{});
    tasks.push_back({left + 1, mid, task.end, task.depth + 1});
    tasks.push_back({left, task.begin, mid, task.depth + 1});
  }

  bvh.face_ids_ = std::move(order);
  bvh.LoadCorners(mesh);
  return bvh;
}

void TriangleBvh::LoadCorners(const Mesh& mesh) {
  triangles_.resize(face_ids_.size());
  for (size_t i = 0; i < face_ids_.size(); ++i) {
    const Face& f = mesh.faces[face_ids_[i]];
    triangles_[i] = {mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]};
  }
}

Status TriangleBvh::Refit(const Mesh& mesh) {
  EQMESH_RETURN_IF_ERROR(ValidateForBvh(mesh));
  if (mesh.faces.size() != face_ids_.size()) {
    return InvalidArgument("refit: " + std::to_string(mesh.faces.size()) + " faces, the tree has " +
                           std::to_string(face_ids_.size()));
  }
  LoadCorners(mesh);
  Box all;
  for (size_t i = 0; i < triangles_.size(); ++i) {
    all.Grow(triangles_[i].v0);
    all.Grow(triangles_[i].v1);
    all.Grow(triangles_[i].v2);
  }
  scale_ = std::max((all.hi - all.lo).norm(), std::numeric_limits<double>::min());
  const double pad = 1e-9 * scale_;
  // Children follow their parent in the array (Build pushes them later), so a
  // backward sweep sees both children before their parent. Padding each box by
  // the same amount commutes with the union (rounding is monotone), so an
  // interior box is its children's union, as Build pads its triangles' union.
  for (size_t k = nodes_.size(); k-- > 0;) {
    Node& node = nodes_[k];
    if (node.count > 0) {
      Box box;
      for (uint32_t i = node.first; i < node.first + node.count; ++i) {
        box.Grow(triangles_[i].v0);
        box.Grow(triangles_[i].v1);
        box.Grow(triangles_[i].v2);
      }
      node.lo = box.lo - Vec3::Constant(pad);
      node.hi = box.hi + Vec3::Constant(pad);
    } else {
      const Node& left = nodes_[node.first];
      const Node& right = nodes_[node.first + 1];
      node.lo = left.lo.cwiseMin(right.lo);
      node.hi = left.hi.cwiseMax(right.hi);
    }
  }
  return Status::Ok();
}

BoundingBox TriangleBvh::bounds() const {
  BoundingBox box;
  if (nodes_.empty()) return box;
  const double pad = 1e-9 * scale_;
  box.min = nodes_[0].lo + Vec3::Constant(pad);
  box.max = nodes_[0].hi - Vec3::Constant(pad);
  return box;
}

template <typename Filter>
ClosestPointResult TriangleBvh::ClosestPointImpl(const Vec3& p, double max_dist,
                                                 const Filter& filter) const {
  ClosestPointResult best;
  if (nodes_.empty() || !p.allFinite() || !(max_dist >= 0.0)) return best;
  double best_d2 = max_dist * max_dist;
  struct Entry {
    uint32_t node;
    double d2;
  };
  Entry stack[kStackSize];
  int top = 0;
  stack[top++] = {0, SquaredDistanceToBox(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 > best_d2) continue;
    const Node& node = nodes_[e.node];
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) {
        if (!filter(face_ids_[i])) continue;
        const Triangle& tri = triangles_[i];
        std::array<double, 3> bary;
        const Vec3 q = ClosestPointOnTriangle(p, tri.v0, tri.v1, tri.v2, &bary);
        const double d2 = (q - p).squaredNorm();
        if (d2 < best_d2 || (!best.found() && d2 <= best_d2)) {
          best_d2 = d2;
          best = {face_ids_[i], q, bary, d2};
        }
      }
      continue;
    }
    const uint32_t l = node.first, r = node.first + 1;
    const double dl = SquaredDistanceToBox(p, nodes_[l].lo, nodes_[l].hi);
    const double dr = SquaredDistanceToBox(p, nodes_[r].lo, nodes_[r].hi);
    // Push the farther child first so the nearer one is searched first and
    // tightens best_d2 before the other is considered.
    const bool left_near = dl <= dr;
    const Entry near_e = left_near ? Entry{l, dl} : Entry{r, dr};
    const Entry far_e = left_near ? Entry{r, dr} : Entry{l, dl};
    if (far_e.d2 <= best_d2) stack[top++] = far_e;
    if (near_e.d2 <= best_d2) stack[top++] = near_e;
  }
  return best;
}

ClosestPointResult TriangleBvh::ClosestPoint(const Vec3& p, double max_dist) const {
  return ClosestPointImpl(p, max_dist, [](uint32_t) { return true; });
}

ClosestPointResult TriangleBvh::ClosestPointFiltered(const Vec3& p,
                                                     const std::function<bool(uint32_t)>& filter,
                                                     double max_dist) const {
  return ClosestPointImpl(p, max_dist, filter);
}

namespace {

// Slab test; NaN-free because axes with dir == 0 are handled separately.
bool RayHitsBox(const Vec3& o, const Vec3& dir, const Vec3& inv, const Vec3& lo, const Vec3& hi,
                double tmin, double tmax) {
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double t0 = (lo[k] - o[k]) * inv[k];
    double t1 = (hi[k] - o[k]) * inv[k];
    if (t0 > t1) std::swap(t0, t1);
    tmin = std::max(tmin, t0);
    tmax = std::min(tmax, t1);
    if (tmin > tmax) return false;
  }
  return true;
}

// Möller–Trumbore with an inclusive epsilon on the barycentric range.
bool IntersectTriangle(const Vec3& o, const Vec3& dir, const TriangleBvh::Triangle& tri,
                       double tmin, double tmax, RayHit* hit) {
  const Vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
  const Vec3 pv = dir.cross(e2);
  const double det = e1.dot(pv);
  // Ray (nearly) in the triangle's plane, or a degenerate triangle: no
  // transversal crossing; the neighbouring faces report it.
  if (!(std::abs(det) > 1e-12 * dir.norm() * e1.norm() * e2.norm())) return false;
  const double inv_det = 1.0 / det;
  const Vec3 tv = o - tri.v0;
  const double u = tv.dot(pv) * inv_det;
  if (u < -kBaryEps || u > 1.0 + kBaryEps) return false;
  const Vec3 qv = tv.cross(e1);
  const double v = dir.dot(qv) * inv_det;
  if (v < -kBaryEps || u + v > 1.0 + kBaryEps) return false;
  const double t = e2.dot(qv) * inv_det;
  if (!(t >= tmin && t <= tmax)) return false;
  // Report a proper barycentric triple even for the epsilon-outside hits.
  double b0 = std::max(0.0, 1.0 - u - v), b1 = std::max(0.0, u), b2 = std::max(0.0, v);
  const double sum = b0 + b1 + b2;
  hit->t = t;
  hit->barycentric = {b0 / sum, b1 / sum, b2 / sum};
  return true;
}

double MinBarycentric(const RayHit& h) {
  return std::min({h.barycentric[0], h.barycentric[1], h.barycentric[2]});
}

}  // namespace

// Calls visit(slot, &tmax) for every triangle slot whose leaf box the ray
// segment meets; visit may shrink tmax to prune the rest of the traversal.
template <typename Visit>
void TriangleBvh::VisitRay(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                           Visit&& visit) const {
  if (nodes_.empty() || !origin.allFinite() || !dir.allFinite() || dir.squaredNorm() == 0.0 ||
      !(tmin <= tmax))
    return;
  const Vec3 inv = dir.cwiseInverse();  // inf entries are never used (see RayHitsBox)
  uint32_t stack[kStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!RayHitsBox(origin, dir, inv, node.lo, node.hi, tmin, tmax)) continue;
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) visit(i, &tmax);
      continue;
    }
    // Visit the child nearer along the ray first (matters for first-hit pruning).
    const uint32_t l = node.first, r = node.first + 1;
    const bool left_first = (nodes_[l].lo + nodes_[l].hi - nodes_[r].lo - nodes_[r].hi).dot(dir) <= 0.0;
    stack[top++] = left_first ? r : l;
    stack[top++] = left_first ? l : r;
  }
}

void TriangleBvh::RayAllHits(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                             std::vector<RayHit>* hits) const {
  hits->clear();
  VisitRay(origin, dir, tmin, tmax, [&](uint32_t i, double* segment_tmax) {
    RayHit hit;
    if (IntersectTriangle(origin, dir, triangles_[i], tmin, *segment_tmax, &hit)) {
      hit.face = face_ids_[i];
      hits->push_back(hit);
    }
  });
  std::sort(hits->begin(), hits->end(), [](const RayHit& a, const RayHit& b) {
    return a.t < b.t || (a.t == b.t && a.face < b.face);
  });
  // Merge runs of hits closer than the tolerance (an edge or vertex crossing
  // seen by every incident face), keeping the one most inside its face.
  const double tol = kMergeFraction * scale_ / dir.norm();
  size_t kept = 0;
  double run_start = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < hits->size(); ++i) {
    const RayHit& h = (*hits)[i];
    if (kept > 0 && h.t - run_start <= tol) {
      if (MinBarycentric(h) > MinBarycentric((*hits)[kept - 1])) (*hits)[kept - 1] = h;
      continue;
    }
    run_start = h.t;
    (*hits)[kept++] = h;
  }
  hits->resize(kept);
}

std::optional<RayHit> TriangleBvh::RayFirstHit(const Vec3& origin, const Vec3& dir, double tmin,
                                               double tmax) const {
  return RayFirstHitImpl(origin, dir, tmin, tmax, [](uint32_t) { return true; });
}

std::optional<RayHit> TriangleBvh::RayFirstHitFiltered(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                                                       const std::function<bool(uint32_t)>& filter) const {
  return RayFirstHitImpl(origin, dir, tmin, tmax, filter);
}

template <typename Filter>
std::optional<RayHit> TriangleBvh::RayFirstHitImpl(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                                                   const Filter& filter) const {
  std::optional<RayHit> best;
  if (!dir.allFinite() || dir.squaredNorm() == 0.0) return best;
  const double tol = kMergeFraction * scale_ / dir.norm();
  VisitRay(origin, dir, tmin, tmax, [&](uint32_t i, double* segment_tmax) {
    RayHit hit;
    if (!filter(face_ids_[i])) return;
    if (!IntersectTriangle(origin, dir, triangles_[i], tmin, *segment_tmax, &hit)) return;
    hit.face = face_ids_[i];
    // Same tie rule as RayAllHits: within tol of the best t, prefer the face
    // the hit is most inside of.
    if (!best || hit.t < best->t - tol ||
        (hit.t <= best->t + tol && MinBarycentric(hit) > MinBarycentric(*best))) {
      best = hit;
      *segment_tmax = std::min(*segment_tmax, hit.t + tol);
    }
  });
  return best;
}

}  // namespace eqmesh

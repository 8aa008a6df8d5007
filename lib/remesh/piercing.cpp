// Normal-mesh piercing and parameter refinement (Guskov et al. 2000); see piercing.h.
#include "remesh/piercing.h"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "remesh/level_domain.h"
#include "remesh/parallel_for.h"
#include "remesh/quality_checks.h"
#include "wavelet/butterfly.h"

namespace eqmesh {
namespace {

// Rays reach this many edge lengths on either side of the prediction.
constexpr double kReach = 1.0;
// The kite of admissible parameters is shrunk toward the edge midpoint by this factor.
constexpr double kKiteShrink = 0.9;
// Minimum quality (4 sqrt 3 A / sum l^2) of a child triangle in the chart.
constexpr double kMinChildQuality = 0.15;
// Largest chart unfolded to reach a hit's input triangle or a midpoint's.
constexpr size_t kMaxChartFaces = 4096;
// Once a level has more faces than the input, forward maps of demoted midpoints
// search a smaller chart: the input triangle under a midpoint then has its
// corners a few face rings away, and a miss (target outside every mapped
// triangle) would otherwise grow the full chart for every such vertex
// (dragon_vrip, 1.8M new vertices: over 10 CPU minutes in one level). A miss
// falls back to the closest input point.
constexpr size_t kMaxFineForwardChartFaces = 256;
// Levels with at least this many faces per input face are refined in 3D (see
// fine_). Measured on the bench meshes: 0.5 (the level after the last one
// coarser than the input's half) folds 3x fewer faces than 1; 0.15 lost up to
// 20 dB where coarse levels still need the charts' protection on thin parts.
constexpr double kFineLevelFaceRatio = 0.5;
// Placement repair: sweeps over the suspect vertices, hits tried per vertex,
// and how far from its edge's 3D middle a vertex may sit (0.6: within the
// middle 80 % of the edge).
constexpr int kRepairPasses = 3;
constexpr size_t kRepairCandidates = 8;
constexpr double kMaxLopsidedness = 0.6;
// Relaxed candidates: how far toward its neighbours' centroid a vertex moves.
constexpr double kRelaxBlends[] = {1.0, 0.5};

using Vec3d = Eigen::Vector3d;

struct EdgeChoice {
  Vec3 position = Vec3::Zero();
  Vec3d u = Vec3d::Zero();  // parameter in the left face's chart
  VertexKind kind = VertexKind::kNonNormal;
  bool needs_forward = false;
};

double Quality2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double denom = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(denom > 0.0)) return 0.0;
  return 2.0 * std::sqrt(3.0) * Orient2d(a, b, c) / denom;
}

Vec3d Midpoint(int slot) {
  Vec3d u = Vec3d::Zero();
  u[slot] = 0.5;
  u[(slot + 1) % 3] = 0.5;
  return u;
}

// An input triangle's chart image must keep its orientation. One that flips was
// unfolded inconsistently (its corners reached around a vertex of valence != 6
// along different paths), and a parameter interpolated in it is meaningless:
// horse, a leg vertex forward-mapped through such a triangle landed on another
// patch and stayed a spike at every level (78 -> 94 dB once refused).
bool ImageIsConsistent(const Vec2 (&c)[3]) { return Orient2d(c[0], c[1], c[2]) > 0.0; }

void ClampBary(Vec3d* b) {
  *b = b->cwiseMax(0.0);
  const double s = b->sum();
  *b = s > 0.0 ? Vec3d(*b / s) : Vec3d::Constant(1.0 / 3.0);
}

class LevelRefiner {
 public:
  LevelRefiner(const SemiRegularHierarchy& h, int j, const InputSurface& s,
               std::vector<Vec3>* positions, std::vector<ParamPoint>* params)
      : h_(h), j_(j), s_(s), dom_(h, j), pos_(*positions), params_(*params) {
    fine_ = static_cast<double>(dom_.faces().size()) >= kFineLevelFaceRatio * static_cast<double>(s.mesh->faces.size());
  }

  void Run(std::vector<Vec3>* positions, std::vector<VertexKind>* kinds, LevelStats* stats);
  std::vector<ParamPoint> TakeParams() { return std::move(params_out_); }

 private:
  void BuildBuckets();
  EdgeChoice PierceEdge(uint32_t k, Chart* chart) const;
  std::vector<EdgeChoice> NormalCandidates(uint32_t k, Chart* chart, size_t limit) const;
  EdgeChoice MidpointChoice(uint32_t k) const;
  bool SurfaceParam(uint32_t k, const Vec3& x, uint32_t face, const std::array<double, 3>& bary, Chart* chart,
                    Vec3d* u) const;
  bool RelaxedChoice(uint32_t k, double blend, Chart* chart, EdgeChoice* out) const;
  EdgeChoice BoundaryPoint(uint32_t k) const;
  bool InKite(const Vec3d& u, int slot) const;
  Vec3d DiamondParam(uint32_t k, const Vec3& x) const;
  Vec3 FineMidpoint(uint32_t k) const;
  std::optional<RayHit> NearestHit(const Vec3& p, const Vec3& n, double reach) const;
  bool FacesAlong(uint32_t input_face, const Vec3& n) const;
  Vec3 ForwardMap(uint32_t root, const Vec3d& u, const Vec3& fallback_near, Chart* chart) const;
  Vec3d EdgePointIn(uint32_t f, int i) const;
  bool ChildrenValid(uint32_t f) const;
  void DemoteInvalidFaces();
  struct PlacementScore {
    size_t folds = 0;
    bool lopsided = false;
    double error = 0.0;
    bool operator<(const PlacementScore& o) const {
      if (folds != o.folds) return folds < o.folds;
      if (lopsided != o.lopsided) return !lopsided;
      return error < o.error;
    }
  };
  // Returns the level-(j+1) faces still folded.
  std::vector<uint32_t> RepairPlacements();
  bool TryAlternatives(uint32_t k, const PlacementScore& before, Chart* chart);
  double Lopsidedness(uint32_t k) const;
  PlacementScore ScorePlacement(uint32_t k) const;
  const Vec3& FinePosition(uint32_t v) const;
  bool Folded(uint32_t child, double* error = nullptr) const;
  std::array<uint32_t, 6> FacesAround(uint32_t k) const;
  size_t FoldsAround(uint32_t k, double* error = nullptr) const;
  void ForwardMapDemoted();
  std::array<std::array<Vec3d, 3>, 4> Children(uint32_t f) const;
  ParamPoint Relocate(uint32_t f, uint32_t x) const;
  bool RelocateBoundary(uint32_t f, uint32_t x, ParamPoint* out) const;
  void UpdateParams(std::vector<ParamPoint>* next) const;
  double RmsError(const std::vector<Vec3>& fine_pos, const std::vector<ParamPoint>& next) const;

  const SemiRegularHierarchy& h_;
  const int j_;
  const InputSurface& s_;
  const LevelDomain dom_;
  const std::vector<Vec3>& pos_;
  const std::vector<ParamPoint>& params_;
  std::vector<uint32_t> bucket_offsets_, bucket_items_;
  std::vector<Vec3> predicted_;
  std::vector<LocalFrame> frames_;
  std::vector<EdgeChoice> choice_;
  std::vector<ParamPoint> params_out_;
  // A level with at least kFineLevelFaceRatio faces per input face: hits are validated and
  // demoted midpoints placed in 3D (DiamondParam, FineMidpoint) instead of
  // through charts.
  bool fine_ = false;
};

void LevelRefiner::BuildBuckets() {
  const size_t nf = dom_.faces().size();
  bucket_offsets_.assign(nf + 1, 0);
  for (const ParamPoint& p : params_) ++bucket_offsets_[p.face + 1];
  for (size_t f = 0; f < nf; ++f) bucket_offsets_[f + 1] += bucket_offsets_[f];
  bucket_items_.resize(params_.size());
  std::vector<uint32_t> fill(bucket_offsets_.begin(), bucket_offsets_.end() - 1);
  for (uint32_t x = 0; x < params_.size(); ++x) bucket_items_[fill[params_[x].face]++] = x;
}

bool LevelRefiner::InKite(const Vec3d& u, int slot) const {
  const Vec2 a = ReferenceCorner(slot), b = ReferenceCorner((slot + 1) % 3), c = ReferenceCorner((slot + 2) % 3);
  const Vec2 g = (a + b + c) / 3.0, g2 = (2.0 * a + 2.0 * b - c) / 3.0, m = 0.5 * (a + b);
  const Vec2 p = m + (ToReference2d(u) - m) / kKiteShrink;
  return Orient2d(a, g2, p) >= 0.0 && Orient2d(g2, b, p) >= 0.0 && Orient2d(b, g, p) >= 0.0 &&
         Orient2d(g, a, p) >= 0.0;
}

// Every admissible normal position for odd vertex k (interior edges only),
// closest to the prediction first; at most `limit`.
std::vector<EdgeChoice> LevelRefiner::NormalCandidates(uint32_t k, Chart* chart, size_t limit) const {
  const EdgeSides& sides = dom_.Sides(k);
  const Edge& e = h_.OddEdge(j_, k);
  const Vec3& p = predicted_[k];
  const Vec3& n = frames_[k].normal;
  const double reach = kReach * (pos_[e[0]] - pos_[e[1]]).norm();
  std::vector<RayHit> hits;
  s_.bvh->RayAllHits(p - reach * n, n, 0.0, 2.0 * reach, &hits);
  std::sort(hits.begin(), hits.end(),
            [reach](const RayHit& x, const RayHit& y) { return std::abs(x.t - reach) < std::abs(y.t - reach); });
  std::vector<EdgeChoice> out;
  if (!hits.empty() && !fine_) chart->Reset(sides.left);
  for (const RayHit& hit : hits) {
    if (out.size() >= limit) break;
    // In 3D the diamond test cannot tell a thin part's two sides apart (both
    // project into it): there the input must face the way the prediction does.
    if (fine_ && !FacesAlong(hit.face, n)) continue;
    EdgeChoice c;
    c.position = p + (hit.t - reach) * n;
    c.kind = VertexKind::kNormal;
    if (SurfaceParam(k, c.position, hit.face, hit.barycentric, chart, &c.u) && InKite(c.u, sides.left_slot)) {
      out.push_back(c);
    }
  }
  return out;
}

// Parameter (left face of edge k's chart, reset by the caller) of the surface
// point x = input triangle `face` at `bary`; false where no chart holds it.
bool LevelRefiner::SurfaceParam(uint32_t k, const Vec3& x, uint32_t face, const std::array<double, 3>& bary,
                                Chart* chart, Vec3d* u) const {
  if (fine_) {
    *u = DiamondParam(k, x);
    return true;
  }
  const Face& tri = s_.mesh->faces[face];
  *u = Vec3d::Zero();
  Vec2 c2[3];
  for (int i = 0; i < 3; ++i) {
    Vec3d ui;
    if (!chart->Map(params_[tri[i]], &ui, kMaxChartFaces)) return false;
    *u += bary[i] * ui;
    c2[i] = ToReference2d(ui);
  }
  return ImageIsConsistent(c2);
}

// Untangling candidate for a repair: the surface point closest to the vertex
// moved `blend` of the way to the average of its six level-(j+1) neighbours
// (non-normal).
bool LevelRefiner::RelaxedChoice(uint32_t k, double blend, Chart* chart, EdgeChoice* out) const {
  const uint32_t self = static_cast<uint32_t>(pos_.size()) + k;
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (uint32_t f : FacesAround(k)) {
    for (uint32_t v : h_.Faces(j_ + 1)[f]) {
      if (v == self) continue;
      sum += FinePosition(v);
      ++count;
    }
  }
  // Same-facing input triangles only, so a thin part's other side is never taken.
  const Vec3& n = frames_[k].normal;
  const Vec3 target = (1.0 - blend) * choice_[k].position + blend * (sum / count);
  const Edge& e = h_.OddEdge(j_, k);
  const double reach = (pos_[e[0]] - pos_[e[1]]).norm();
  const ClosestPointResult cp =
      s_.bvh->ClosestPointFiltered(target, [&](uint32_t f) { return FacesAlong(f, n); }, reach);
  if (!cp.found()) return false;
  chart->Reset(dom_.Sides(k).left);
  out->position = cp.point;
  out->kind = VertexKind::kNonNormal;
  out->needs_forward = false;
  if (!SurfaceParam(k, cp.point, cp.face, cp.barycentric, chart, &out->u)) return false;
  // On 3D-refined levels the diamond is the 3D one and cannot reach a thin
  // part's other side, so the whole diamond is admissible there.
  if (fine_) {
    const int a = dom_.Sides(k).left_slot, b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec3d& u = out->u;
    return std::min(u[a], u[b]) >= std::max(0.0, -u[c]);
  }
  return InKite(out->u, dom_.Sides(k).left_slot);
}


EdgeChoice LevelRefiner::MidpointChoice(uint32_t k) const {
  EdgeChoice out;
  out.u = Midpoint(dom_.Sides(k).left_slot);
  out.kind = VertexKind::kNonNormal;
  out.needs_forward = true;
  return out;
}

EdgeChoice LevelRefiner::PierceEdge(uint32_t k, Chart* chart) const {
  if (dom_.Sides(k).right == kNoNeighbour) return BoundaryPoint(k);
  const std::vector<EdgeChoice> normal = NormalCandidates(k, chart, 1);
  return normal.empty() ? MidpointChoice(k) : normal.front();
}

// Chart coordinates (left face of edge k) of a point near the edge's diamond,
// from its projection onto the level-j triangles themselves: on levels finer
// than the input the remesh lies within a fraction of an input triangle of the
// surface, and the 3D diamond is a better chart than unfolding many small faces
// around the input triangle a hit lies in.
Vec3d LevelRefiner::DiamondParam(uint32_t k, const Vec3& x) const {
  const EdgeSides& sides = dom_.Sides(k);
  auto barycentric = [&](uint32_t f) {
    const Face& t = dom_.faces()[f];
    const Vec3& a = pos_[t[0]];
    const Vec3 e1 = pos_[t[1]] - a, e2 = pos_[t[2]] - a, d = x - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(std::abs(det) > 0.0)) return Vec3d(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
    const double b1 = (d22 * d.dot(e1) - d12 * d.dot(e2)) / det;
    const double b2 = (d11 * d.dot(e2) - d12 * d.dot(e1)) / det;
    return Vec3d(1.0 - b1 - b2, b1, b2);
  };
  const Vec3d left = barycentric(sides.left);
  if (left[(sides.left_slot + 2) % 3] >= 0.0) return left;
  const Vec3d right = barycentric(sides.right);
  // Inverse of LevelDomain::LeftToRight.
  const int a = sides.left_slot, b = (a + 1) % 3, c = (a + 2) % 3, r = sides.right_slot;
  Vec3d u;
  u[c] = -right[(r + 2) % 3];
  u[b] = right[r] + right[(r + 2) % 3];
  u[a] = right[(r + 1) % 3] + right[(r + 2) % 3];
  return u;
}

// Non-normal vertex on a level finer than the input: pierce from the edge's
// 3D midpoint, else take the closest surface point to it.
Vec3 LevelRefiner::FineMidpoint(uint32_t k) const {
  const Edge& e = h_.OddEdge(j_, k);
  const Vec3 m = 0.5 * (pos_[e[0]] + pos_[e[1]]);
  const Vec3& n = frames_[k].normal;
  const double reach = 0.5 * (pos_[e[0]] - pos_[e[1]]).norm();
  const std::optional<RayHit> hit = NearestHit(m, n, reach);
  if (hit) return m + hit->t * n;
  const ClosestPointResult cp = s_.bvh->ClosestPoint(m);
  return cp.found() ? cp.point : m;
}

std::optional<RayHit> LevelRefiner::NearestHit(const Vec3& p, const Vec3& n, double reach) const {
  std::vector<RayHit> hits;
  s_.bvh->RayAllHits(p - reach * n, n, 0.0, 2.0 * reach, &hits);
  std::optional<RayHit> best;
  for (RayHit h : hits) {
    h.t -= reach;
    if (!best || std::abs(h.t) < std::abs(best->t)) best = h;
  }
  return best;
}

bool LevelRefiner::FacesAlong(uint32_t input_face, const Vec3& n) const {
  const Face& g = s_.mesh->faces[input_face];
  const std::vector<Vec3>& x = s_.mesh->positions;
  return (x[g[1]] - x[g[0]]).cross(x[g[2]] - x[g[0]]).dot(n) > 0.0;
}

// Boundary edge: the parametric midpoint of the input boundary polyline between
// the edge's endpoints (input boundary vertices sit exactly on the edge).
EdgeChoice LevelRefiner::BoundaryPoint(uint32_t k) const {
  const EdgeSides& sides = dom_.Sides(k);
  const uint32_t f = sides.left;
  const int a = sides.left_slot, b = (a + 1) % 3, c = (a + 2) % 3;
  const Face& face = dom_.faces()[f];
  std::vector<std::pair<double, uint32_t>> chain;
  for (uint32_t n = bucket_offsets_[f]; n < bucket_offsets_[f + 1]; ++n) {
    const uint32_t x = bucket_items_[n];
    const ParamPoint& p = params_[x];
    if (s_.is_boundary[x] && p.bary[c] == 0.0 && p.bary[a] > 0.0 && p.bary[b] > 0.0) {
      chain.push_back({p.bary[b], x});
    }
  }
  std::sort(chain.begin(), chain.end());
  double t0 = 0.0, t1 = 1.0;
  Vec3 p0 = pos_[face[a]], p1 = pos_[face[b]];
  for (const auto& [t, x] : chain) {
    if (t <= 0.5) {
      t0 = t;
      p0 = s_.mesh->positions[x];
    } else {
      t1 = t;
      p1 = s_.mesh->positions[x];
      break;
    }
  }
  EdgeChoice out;
  const double w = t1 > t0 ? (0.5 - t0) / (t1 - t0) : 0.5;
  out.position = (1.0 - w) * p0 + w * p1;
  out.u = Midpoint(a);
  out.kind = VertexKind::kBoundary;
  return out;
}

// Surface point at chart parameter u of face `root`: the input triangle whose
// chart image contains u.
Vec3 LevelRefiner::ForwardMap(uint32_t root, const Vec3d& u, const Vec3& fallback_near, Chart* chart) const {
  chart->Reset(root);
  const Vec2 target = ToReference2d(u);
  double best = -1e300;
  Vec3 best_point = Vec3::Zero();
  const size_t max_faces = dom_.faces().size() > s_.mesh->faces.size() ? kMaxFineForwardChartFaces : kMaxChartFaces;
  for (size_t visit = 0; visit < max_faces && (visit < chart->size() || chart->Grow()); ++visit) {
    const uint32_t f = chart->face(visit);
    for (uint32_t n = bucket_offsets_[f]; n < bucket_offsets_[f + 1]; ++n) {
      const uint32_t x = bucket_items_[n];
      for (uint32_t q = s_.face_offsets[x]; q < s_.face_offsets[x + 1]; ++q) {
        const Face& tri = s_.mesh->faces[s_.vertex_faces[q]];
        Vec2 c2[3];
        bool mapped = true;
        for (int i = 0; i < 3 && mapped; ++i) {
          Vec3d ui;
          mapped = chart->Map(params_[tri[i]], &ui, max_faces);
          c2[i] = ToReference2d(ui);
        }
        Vec3d b;
        if (!mapped || !ImageIsConsistent(c2) || !Barycentric2d(target, c2[0], c2[1], c2[2], &b)) continue;
        if (b.minCoeff() > best) {
          best = b.minCoeff();
          ClampBary(&b);
          best_point = b[0] * s_.mesh->positions[tri[0]] + b[1] * s_.mesh->positions[tri[1]] +
                       b[2] * s_.mesh->positions[tri[2]];
        }
      }
    }
    // The first face in breadth-first order whose input triangles contain the
    // target wins: farther faces are reached through more unfoldings, and around
    // a vertex of valence != 6 those disagree, so a far triangle can appear to
    // contain the target with a larger margin than the right one (stanford-bunny:
    // a base-edge midpoint placed 3 % of the diagonal away from its own patch,
    // a spike that no finer level removed).
    if (best >= -1e-9) break;
  }
  if (best > -0.5) return best_point;
  const ClosestPointResult cp = s_.bvh->ClosestPoint(fallback_near);
  return cp.found() ? cp.point : fallback_near;
}

Vec3d LevelRefiner::EdgePointIn(uint32_t f, int i) const {
  const uint32_t k = dom_.EdgeOf(f, i);
  const EdgeSides& sides = dom_.Sides(k);
  if (sides.left == f && sides.left_slot == i) return choice_[k].u;
  return dom_.LeftToRight(k, choice_[k].u);
}

std::array<std::array<Vec3d, 3>, 4> LevelRefiner::Children(uint32_t f) const {
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const Vec3d q0 = EdgePointIn(f, 0), q1 = EdgePointIn(f, 1), q2 = EdgePointIn(f, 2);
  return {{{id.col(0), q0, q2}, {q0, id.col(1), q1}, {q2, q1, id.col(2)}, {q0, q1, q2}}};
}

bool LevelRefiner::ChildrenValid(uint32_t f) const {
  for (const auto& child : Children(f)) {
    const Vec2 a = ToReference2d(child[0]), b = ToReference2d(child[1]), c = ToReference2d(child[2]);
    if (Quality2d(a, b, c) < kMinChildQuality) return false;
  }
  return true;
}

// A face whose children would fold or degenerate gets its worst normal edge
// moved back to the parametric midpoint, until all faces are valid (midpoints
// alone always are).
void LevelRefiner::DemoteInvalidFaces() {
  bool changed = true;
  while (changed) {
    changed = false;
    for (uint32_t f = 0; f < dom_.faces().size(); ++f) {
      while (!ChildrenValid(f)) {
        int worst = -1;
        double worst_dist = -1.0;
        for (int i = 0; i < 3; ++i) {
          const uint32_t k = dom_.EdgeOf(f, i);
          if (choice_[k].kind != VertexKind::kNormal) continue;
          const double d = (ToReference2d(EdgePointIn(f, i)) - ToReference2d(Midpoint(i))).norm();
          if (d > worst_dist) {
            worst_dist = d;
            worst = i;
          }
        }
        if (worst < 0) break;  // only midpoints left: cannot happen for valid charts
        const uint32_t k = dom_.EdgeOf(f, worst);
        choice_[k].u = Midpoint(dom_.Sides(k).left_slot);
        choice_[k].kind = VertexKind::kNonNormal;
        choice_[k].needs_forward = true;
        changed = true;
      }
    }
  }
}

bool LevelRefiner::RelocateBoundary(uint32_t f, uint32_t x, ParamPoint* out) const {
  const ParamPoint& p = params_[x];
  int zero = -1;
  for (int i = 0; i < 3; ++i) {
    if (p.bary[i] == 0.0) zero = i;
  }
  if (zero < 0) return false;
  const int e = (zero + 1) % 3;
  if (dom_.Neighbour(f, e) != kNoNeighbour) return false;
  const double s = p.bary[(e + 1) % 3];  // weight of the edge's second corner
  // Child c of the 1-to-4 split holds corner c at slot c. The first half of the
  // edge lies in child e with m_e at slot e+1; the second in child e+1 with m_e at slot e.
  std::array<double, 3> b{0, 0, 0};
  const bool first_half = s <= 0.5;
  const int child = first_half ? e : (e + 1) % 3;
  if (first_half) {
    b[e] = 1.0 - 2.0 * s;
    b[(e + 1) % 3] = 2.0 * s;
  } else {
    b[e] = 2.0 - 2.0 * s;
    b[(e + 1) % 3] = 2.0 * s - 1.0;
  }
  *out = {static_cast<uint32_t>(4 * f + child), b};
  return true;
}

ParamPoint LevelRefiner::Relocate(uint32_t f, uint32_t x) const {
  ParamPoint out;
  if (s_.is_boundary[x] && RelocateBoundary(f, x, &out)) return out;
  const ParamPoint& p = params_[x];
  const Vec2 q = ToReference2d(Vec3d(p.bary[0], p.bary[1], p.bary[2]));
  double best = -1e300;
  auto consider = [&](uint32_t face, const std::array<std::array<Vec3d, 3>, 4>& kids, const Eigen::Matrix3d& to_f) {
    for (int c = 0; c < 4; ++c) {
      Vec3d b;
      if (!Barycentric2d(q, ToReference2d(to_f * kids[c][0]), ToReference2d(to_f * kids[c][1]),
                         ToReference2d(to_f * kids[c][2]), &b)) {
        continue;
      }
      if (b.minCoeff() > best) {
        best = b.minCoeff();
        out.face = 4 * face + static_cast<uint32_t>(c);
        out.bary = {b[0], b[1], b[2]};
      }
    }
  };
  consider(f, Children(f), Eigen::Matrix3d::Identity());
  if (best < -1e-12) {
    for (int i = 0; i < 3; ++i) {
      const uint32_t g = dom_.Neighbour(f, i);
      if (g != kNoNeighbour) consider(g, Children(g), dom_.NeighbourCorners(f, i));
    }
  }
  Vec3d b(out.bary[0], out.bary[1], out.bary[2]);
  ClampBary(&b);
  out.bary = {b[0], b[1], b[2]};
  return out;
}

void LevelRefiner::ForwardMapDemoted() {
  ParallelFor(choice_.size(), [&](size_t begin, size_t end, size_t) {
    Chart chart(dom_);
    for (size_t k = begin; k < end; ++k) {
      EdgeChoice& c = choice_[k];
      if (!c.needs_forward) continue;
      c.position = fine_ ? FineMidpoint(static_cast<uint32_t>(k))
                         : ForwardMap(dom_.Sides(static_cast<uint32_t>(k)).left, c.u, predicted_[k], &chart);
      c.needs_forward = false;
    }
  });
}

void LevelRefiner::Run(std::vector<Vec3>* positions, std::vector<VertexKind>* kinds, LevelStats* stats) {
  BuildBuckets();
  const StencilTable stencils = BuildButterflyStencils(h_, j_);
  ApplyStencils(stencils, pos_, &predicted_);
  frames_ = ComputeOddFrames(h_, j_, stencils, pos_);
  const size_t n_edges = dom_.num_edges();
  choice_.resize(n_edges);
  ParallelFor(n_edges, [&](size_t begin, size_t end, size_t) {
    Chart chart(dom_);
    for (size_t k = begin; k < end; ++k) choice_[k] = PierceEdge(static_cast<uint32_t>(k), &chart);
  });
  DemoteInvalidFaces();
  ForwardMapDemoted();
  stats->folded_faces = RepairPlacements();
  for (const EdgeChoice& c : choice_) {
    positions->push_back(c.position);
    kinds->push_back(c.kind);
  }
  std::vector<ParamPoint> next(params_.size());
  UpdateParams(&next);
  stats->rms_error = RmsError(*positions, next);
  params_out_ = std::move(next);
}

const Vec3& LevelRefiner::FinePosition(uint32_t v) const {
  return v < pos_.size() ? pos_[v] : choice_[v - pos_.size()].position;
}

// A level-(j+1) face folds when it faces away from the input at the closest
// point of its centroid (the remesh check, quality_checks.h); degenerate counts.
// Also returns the face's area times its centroid's squared distance.
bool LevelRefiner::Folded(uint32_t child, double* error) const {
  const Face& t = h_.Faces(j_ + 1)[child];
  const Vec3& a = FinePosition(t[0]);
  const Vec3& b = FinePosition(t[1]);
  const Vec3& c = FinePosition(t[2]);
  if (!((b - a).cross(c - a).squaredNorm() > 0.0)) return true;
  return FacesAwayFromInput(*s_.bvh, *s_.mesh, a, b, c, error);
}

// The six level-(j+1) faces around odd vertex k (three children of each side).
std::array<uint32_t, 6> LevelRefiner::FacesAround(uint32_t k) const {
  const EdgeSides& e = dom_.Sides(k);
  const uint32_t l = 4 * e.left, r = 4 * e.right;
  return {l + e.left_slot, l + (e.left_slot + 1) % 3, l + 3, r + e.right_slot, r + (e.right_slot + 1) % 3, r + 3};
}

size_t LevelRefiner::FoldsAround(uint32_t k, double* error) const {
  size_t n = 0;
  for (uint32_t f : FacesAround(k)) n += Folded(f, error);
  return n;
}

// How far odd vertex k sits from the middle of its edge in 3D: 0 at the 3D
// midpoint, 1 at an endpoint.
double LevelRefiner::Lopsidedness(uint32_t k) const {
  const Edge& e = h_.OddEdge(j_, k);
  const Vec3& m = choice_[k].position;
  const double da = (m - pos_[e[0]]).norm(), db = (m - pos_[e[1]]).norm();
  return da + db > 0.0 ? std::abs(da - db) / (da + db) : 1.0;
}

// Placement score of odd vertex k, smaller is better: folded faces around it
// first, then whether it sits near an end of its edge, then the faces' error.
LevelRefiner::PlacementScore LevelRefiner::ScorePlacement(uint32_t k) const {
  PlacementScore s;
  s.folds = FoldsAround(k, &s.error);
  s.lopsided = Lopsidedness(k) > kMaxLopsidedness;
  return s;
}

// Folds at a level multiply by four at every finer one (their children are
// pierced from folded predictions), and so does a vertex placed next to an end
// of its edge: where the parameterization is compressed the edges around it
// then never shrink (armadillo claws: 0.02 of the diagonal from level 2 to 5).
// So each level is cleaned before the next: an odd vertex of a folded face, or
// one within kMaxLopsidedness of an end of its edge, tries its other admissible
// hits, the parametric midpoint and the surface point closest to its
// neighbours' average, and keeps the best ScorePlacement. Departure from Guskov
// et al., who take the hit closest to the prediction.
std::vector<uint32_t> LevelRefiner::RepairPlacements() {
  const size_t nf = dom_.faces().size();
  std::vector<uint8_t> suspect(choice_.size(), 0);
  std::vector<uint8_t> touched(nf, 0);  // level-j faces whose children may be folded
  ParallelFor(nf, [&](size_t begin, size_t end, size_t) {
    for (size_t f = begin; f < end; ++f) {
      for (uint32_t c = 0; c < 4; ++c) {
        if (!Folded(static_cast<uint32_t>(4 * f + c))) continue;
        touched[f] = 1;
        for (int i = 0; i < 3; ++i) suspect[dom_.EdgeOf(static_cast<uint32_t>(f), i)] = 1;
      }
    }
  });
  for (uint32_t k = 0; k < choice_.size(); ++k) {
    if (Lopsidedness(k) > kMaxLopsidedness) suspect[k] = 1;
  }
  Chart chart(dom_);
  for (int pass = 0; pass < kRepairPasses; ++pass) {
    bool changed = false;
    for (uint32_t k = 0; k < choice_.size(); ++k) {
      if (!suspect[k] || dom_.Sides(k).right == kNoNeighbour) continue;
      suspect[k] = 0;
      const PlacementScore before = ScorePlacement(k);
      if (before.folds == 0 && !before.lopsided) continue;
      if (TryAlternatives(k, before, &chart)) {
        changed = true;
        // The neighbours' faces changed too: look at them again.
        for (uint32_t f : {dom_.Sides(k).left, dom_.Sides(k).right}) {
          touched[f] = 1;
          for (int i = 0; i < 3; ++i) suspect[dom_.EdgeOf(f, i)] = 1;
        }
      }
    }
    if (!changed) break;
  }
  std::vector<uint32_t> folded;
  for (uint32_t f = 0; f < nf; ++f) {
    if (!touched[f]) continue;
    for (uint32_t c = 0; c < 4; ++c) {
      if (Folded(4 * f + c)) folded.push_back(4 * f + c);
    }
  }
  return folded;
}

bool LevelRefiner::TryAlternatives(uint32_t k, const PlacementScore& before, Chart* chart) {
  std::vector<EdgeChoice> options = NormalCandidates(k, chart, kRepairCandidates);
  EdgeChoice mid = MidpointChoice(k);
  mid.position = fine_ ? FineMidpoint(k) : ForwardMap(dom_.Sides(k).left, mid.u, predicted_[k], chart);
  mid.needs_forward = false;
  options.push_back(mid);
  for (const double blend : kRelaxBlends) {
    EdgeChoice relaxed;
    if (RelaxedChoice(k, blend, chart, &relaxed)) options.push_back(relaxed);
  }
  const EdgeChoice current = choice_[k];
  EdgeChoice best = current;
  PlacementScore best_score = before;
  for (const EdgeChoice& o : options) {
    choice_[k] = o;
    if (!ChildrenValid(dom_.Sides(k).left) || !ChildrenValid(dom_.Sides(k).right)) continue;
    const PlacementScore score = ScorePlacement(k);
    if (score < best_score) {
      best_score = score;
      best = o;
    }
  }
  choice_[k] = best;
  return best.position != current.position;
}

void LevelRefiner::UpdateParams(std::vector<ParamPoint>* next) const {
  const size_t nf = dom_.faces().size();
  ParallelFor(nf, [&](size_t begin, size_t end, size_t) {
    for (size_t f = begin; f < end; ++f) {
      for (uint32_t n = bucket_offsets_[f]; n < bucket_offsets_[f + 1]; ++n) {
        const uint32_t x = bucket_items_[n];
        (*next)[x] = Relocate(static_cast<uint32_t>(f), x);
      }
    }
  });
}

// Remesh error seen from the input vertices (cheap stand-in for Metro).
double LevelRefiner::RmsError(const std::vector<Vec3>& fine_pos, const std::vector<ParamPoint>& next) const {
  const std::vector<Face>& fine = h_.Faces(j_ + 1);
  const double sum = ParallelSum(next.size(), 0.0, [&](size_t begin, size_t end) {
    double local = 0.0;
    for (size_t x = begin; x < end; ++x) {
      const Face& t = fine[next[x].face];
      std::array<double, 3> b;
      const Vec3 q = ClosestPointOnTriangle(s_.mesh->positions[x], fine_pos[t[0]], fine_pos[t[1]], fine_pos[t[2]], &b);
      local += (q - s_.mesh->positions[x]).squaredNorm();
    }
    return local;
  });
  return next.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(next.size()));
}

}  // namespace

InputSurface::InputSurface(const Mesh& m, const TriangleBvh& b, std::vector<uint8_t> boundary)
    : mesh(&m), bvh(&b), is_boundary(std::move(boundary)) {
  face_offsets.assign(m.positions.size() + 1, 0);
  for (const Face& f : m.faces) {
    for (uint32_t v : f) ++face_offsets[v + 1];
  }
  for (size_t v = 0; v < m.positions.size(); ++v) face_offsets[v + 1] += face_offsets[v];
  vertex_faces.resize(face_offsets.back());
  std::vector<uint32_t> fill(face_offsets.begin(), face_offsets.end() - 1);
  for (uint32_t f = 0; f < m.faces.size(); ++f) {
    for (uint32_t v : m.faces[f]) vertex_faces[fill[v]++] = f;
  }
  normals.assign(m.positions.size(), Vec3::Zero());
  for (const Face& f : m.faces) {
    const Vec3 n = (m.positions[f[1]] - m.positions[f[0]]).cross(m.positions[f[2]] - m.positions[f[0]]);
    for (uint32_t v : f) normals[v] += n;
  }
}

void RefineLevel(const SemiRegularHierarchy& hierarchy, int j, const InputSurface& surface,
                 std::vector<Vec3>* positions, std::vector<VertexKind>* kinds, std::vector<ParamPoint>* params,
                 LevelStats* stats) {
  *stats = LevelStats();
  std::vector<Vec3> level = *positions;
  LevelRefiner refiner(hierarchy, j, surface, &level, params);
  refiner.Run(positions, kinds, stats);
  *params = refiner.TakeParams();
}

}  // namespace eqmesh

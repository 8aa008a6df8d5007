// Normal-mesh piercing and parameter refinement (Guskov et al. 2000); see piercing.h.
#include "remesh/piercing.h"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "mesh/mesh_topology.h"
#include "remesh/level_domain.h"
#include "remesh/level_refiner.h"
#include "core/parallel_for.h"
#include "remesh/quality_checks.h"
#include "wavelet/butterfly.h"

namespace eqmesh {
namespace remesh_internal {
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
// falls back to FineMidpoint's surface point.
constexpr size_t kMaxFineForwardChartFaces = 256;
// A forward-mapped midpoint farther than this many edge lengths from its
// butterfly prediction was found through an unfolding that overlaps another
// patch (the chart's angles around a vertex of valence != 6 do not close), not
// on the edge's own patch: FineMidpoint's surface point replaces it.
// Without it dragon_vrip, whose stalled base has thousands of such edges, places
// level-1 vertices 8 % of the diagonal from their edges. The bench meshes reach
// 13.8 edge lengths at most (the bunny, level 4), so 16 leaves their remeshes as
// they are, where 4 and 8 give them slivers (measured:
// bench/log/2026-12-05-remesh-notebook.md).
constexpr double kMidpointReach = 16.0;
// ... and one farther than this many edge lengths from the edge's own midpoint
// too: a prediction can itself lie far off (boundaries, irregular
// neighbourhoods), so a point within 16 edge lengths of it can still be a spike
// 10 edge lengths from its edge (dragon_vrip's canonical copy: 0.8 % of the
// diagonal off the input, 5.5 dB of its PSNR). Mid-size charts send up to 140
// midpoints per remesh 4-17 edge lengths away; 4 leaves every mid-size remesh at
// or above its PSNR and the bench scans within 0.001 dB, where 2 already folds
// faces of the cow (measured: bench/log/2026-12-06-midpoint-reach.md).
constexpr double kMidpointEdgeReach = 4.0;

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
// along different paths), and a parameter interpolated in it is meaningless
// (on the horse it puts a leg vertex on another patch: a spike at every level).
bool ImageIsConsistent(const Vec2 (&c)[3]) { return Orient2d(c[0], c[1], c[2]) > 0.0; }

void ClampBary(Vec3d* b) {
  *b = b->cwiseMax(0.0);
  const double s = b->sum();
  *b = s > 0.0 ? Vec3d(*b / s) : Vec3d::Constant(1.0 / 3.0);
}

}  // namespace


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
  const uint32_t part = fine_ ? EdgePart(k) : kAnyPart;
  for (const RayHit& hit : hits) {
    if (out.size() >= limit) break;
    // In 3D the diamond test cannot tell a thin part's two sides apart (both
    // project into it): there the input must face the way the prediction does,
    // and a part of the input that passes through the diamond is not this one.
    if (fine_ && (!FacesAlong(hit.face, n) || !OnPart(hit.face, part) || !OnEdgeSheet(k, hit.face))) continue;
    EdgeChoice c;
    c.position = p + (hit.t - reach) * n;
    c.kind = VertexKind::kNormal;
    c.on_face = hit.face;
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

// Guskov et al.'s region: the two faces of the edge in `slot` of u's chart.
bool LevelRefiner::InDiamond(const Vec3d& u, int slot) const {
  const int a = slot, b = (slot + 1) % 3, c = (slot + 2) % 3;
  return std::min(u[a], u[b]) >= std::max(0.0, -u[c]);
}

// Surface point of a demoted midpoint of edge k at chart parameter u: the
// forward map's, unless it found no input triangle there or one farther than
// kMidpointReach edge lengths from the prediction or kMidpointEdgeReach from
// the edge's midpoint; then FineMidpoint's.
Vec3 LevelRefiner::MidpointPosition(uint32_t k, const Vec3d& u, Chart* chart, uint32_t* on_face) const {
  if (fine_) return FineMidpoint(k, on_face);
  const Edge& e = h_.OddEdge(j_, k);
  const double length = (pos_[e[0]] - pos_[e[1]]).norm();
  const std::optional<Vec3> mapped =
      ForwardMap(dom_.Sides(k).left, u, predicted_[k], kMidpointReach * length, chart, on_face);
  const Vec3 middle = 0.5 * (pos_[e[0]] + pos_[e[1]]);
  const double edge_reach = kMidpointEdgeReach * length;
  if (mapped && (*mapped - middle).squaredNorm() <= edge_reach * edge_reach) return *mapped;
  return FineMidpoint(k, on_face);
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
  if (std::optional<EdgeChoice> crease = CreasePoint(k)) return *crease;
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

// Non-normal vertex on a level finer than the input (and a coarser one whose
// forward map failed): pierce from the edge's 3D midpoint, else take the
// closest surface point to it.
Vec3 LevelRefiner::FineMidpoint(uint32_t k, uint32_t* on_face) const {
  const Edge& e = h_.OddEdge(j_, k);
  const Vec3 m = 0.5 * (pos_[e[0]] + pos_[e[1]]);
  const Vec3& n = frames_[k].normal;
  const double reach = 0.5 * (pos_[e[0]] - pos_[e[1]]).norm();
  const uint32_t part = EdgePart(k);
  const std::optional<RayHit> hit = NearestHit(m, n, reach, part);
  if (hit) {
    *on_face = hit->face;
    return m + hit->t * n;
  }
  const auto on_part = [&](uint32_t f) { return OnPart(f, part); };
  const ClosestPointResult cp = part == kAnyPart ? s_.bvh->ClosestPoint(m) : s_.bvh->ClosestPointFiltered(m, on_part);
  *on_face = cp.face;
  return cp.found() ? cp.point : m;
}

// The hit of the segment p +- reach * n closest to p, on `part` (kAnyPart: anywhere).
std::optional<RayHit> LevelRefiner::NearestHit(const Vec3& p, const Vec3& n, double reach, uint32_t part) const {
  std::vector<RayHit> hits;
  s_.bvh->RayAllHits(p - reach * n, n, 0.0, 2.0 * reach, &hits);
  std::optional<RayHit> best;
  for (RayHit h : hits) {
    if (!OnPart(h.face, part)) continue;
    h.t -= reach;
    if (!best || std::abs(h.t) < std::abs(best->t)) best = h;
  }
  return best;
}

// The input part edge k remeshes (RemeshParts), kAnyPart for an input of one
// part: the remesh of one part must not land on another that touches or passes
// through it.
uint32_t LevelRefiner::EdgePart(uint32_t k) const {
  return parts_.Of(dom_.Sides(k).left, j_);
}

bool LevelRefiner::OnPart(uint32_t input_face, uint32_t part) const {
  return part == kAnyPart || s_.face_part[input_face] == part;
}

// Whether `input_face` lies within two vertex rings of the input faces under
// edge k's ends (true where either is unknown: a vertex the untangler moved).
// On a level refined in 3D an edge is about as long as the input's or shorter, so the point
// it refines to lies on a face next to its ends' faces; a sheet passing through
// the diamond from elsewhere is not the one the edge remeshes (piercing.h).
bool LevelRefiner::OnEdgeSheet(uint32_t k, uint32_t input_face) const {
  const Edge& e = h_.OddEdge(j_, k);
  const uint32_t fa = e[0] < on_face_.size() ? on_face_[e[0]] : kNoFace;
  const uint32_t fb = e[1] < on_face_.size() ? on_face_[e[1]] : kNoFace;
  if (fa == kNoFace || fb == kNoFace) return true;
  if (input_face == fa || input_face == fb) return true;
  const Mesh& m = *s_.mesh;
  // Vertices within one ring of the target face; then whether a face of fa or
  // fb has a vertex whose faces reach one of them.
  thread_local std::vector<uint32_t> near;
  near.clear();
  for (uint32_t v : m.faces[input_face]) {
    for (uint32_t i = s_.face_offsets[v]; i < s_.face_offsets[v + 1]; ++i) {
      for (uint32_t w : m.faces[s_.vertex_faces[i]]) near.push_back(w);
    }
  }
  std::sort(near.begin(), near.end());
  for (uint32_t f : {fa, fb}) {
    for (uint32_t v : m.faces[f]) {
      for (uint32_t i = s_.face_offsets[v]; i < s_.face_offsets[v + 1]; ++i) {
        for (uint32_t w : m.faces[s_.vertex_faces[i]]) {
          if (std::binary_search(near.begin(), near.end(), w)) return true;
        }
      }
    }
  }
  return false;
}

bool LevelRefiner::FacesAlong(uint32_t input_face, const Vec3& n) const {
  return s_.face_normals[input_face].dot(n) > 0.0;
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

// A tagged edge (semi_regular.h: a base edge along a crease chain, or half of
// one) whose ends still lie on the chain: the chain's arc-length midpoint
// between them (crease_curves.h), at the parametric midpoint of the edge. Only
// tagged edges, so the vertices placed on creases are those the butterfly
// predicts along them.
std::optional<EdgeChoice> LevelRefiner::CreasePoint(uint32_t k) const {
  if (!creases_ || s_.creases.empty() || !h_.IsCreaseOdd(j_, k)) return std::nullopt;
  const Edge& e = h_.OddEdge(j_, k);
  const std::optional<CreaseSite> site =
      s_.creases.SplitSite((*creases_)[e[0]], pos_[e[0]], (*creases_)[e[1]], pos_[e[1]]);
  if (!site) return std::nullopt;
  EdgeChoice out;
  out.position = s_.creases.PositionAt(*site, *s_.mesh, &out.on_face);
  if (!OnPart(out.on_face, EdgePart(k))) return std::nullopt;
  out.u = Midpoint(dom_.Sides(k).left_slot);
  out.kind = VertexKind::kNonNormal;
  out.crease = *site;
  return out;
}

void LevelRefiner::AppendCreasePlaces(std::vector<CreasePlace>* places) const {
  for (const EdgeChoice& c : choice_) {
    CreasePlace place;
    place.site = c.crease;
    places->push_back(place);
  }
}

// Surface point at chart parameter u of face `root`: the input triangle whose
// chart image contains u; none when there is no such triangle or the point lies
// farther than `reach` from `near`.
std::optional<Vec3> LevelRefiner::ForwardMap(uint32_t root, const Vec3d& u, const Vec3& near, double reach,
                                             Chart* chart, uint32_t* on_face) const {
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
        const uint32_t input_face = s_.vertex_faces[q];
        const Face& tri = s_.mesh->faces[input_face];
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
          *on_face = input_face;
          ClampBary(&b);
          best_point = b[0] * s_.mesh->positions[tri[0]] + b[1] * s_.mesh->positions[tri[1]] +
                       b[2] * s_.mesh->positions[tri[2]];
        }
      }
    }
    // The first face in breadth-first order whose input triangles contain the
    // target wins: farther faces are reached through more unfoldings, and around
    // a vertex of valence != 6 those disagree, so a far triangle can appear to
    // contain the target with a larger margin than the right one (on the bunny
    // a base-edge midpoint would land 3 % of the diagonal away from its own
    // patch, a spike that no finer level removes).
    if (best >= -1e-9) break;
  }
  if (best > -0.5 && (best_point - near).squaredNorm() <= reach * reach) return best_point;
  return std::nullopt;
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
      c.position = MidpointPosition(static_cast<uint32_t>(k), c.u, &chart, &c.on_face);
      c.needs_forward = false;
    }
  });
}

void LevelRefiner::Run(const StencilTable& stencils, std::vector<Vec3>* positions, std::vector<uint32_t>* on_faces,
                       std::vector<VertexKind>* kinds, LevelStats* stats) {
  BuildBuckets();
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
    on_faces->push_back(c.on_face);
    kinds->push_back(c.kind);
  }
  std::vector<ParamPoint> next(params_.size());
  UpdateParams(&next);
  stats->rms_error = RmsError(*positions, next);
  params_out_ = std::move(next);
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

}  // namespace remesh_internal

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
  face_normals = FaceCrossProducts(m);
  face_part = FacePartsForFoldTest(m);
  creases = CreaseCurves(m);
  normals.assign(m.positions.size(), Vec3::Zero());
  for (uint32_t f = 0; f < m.faces.size(); ++f) {
    for (uint32_t v : m.faces[f]) normals[v] += face_normals[f];
  }
  if (std::find(is_boundary.begin(), is_boundary.end(), 1) == is_boundary.end()) return;
  const MeshTopology topology(m);
  for (uint32_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.IsBoundaryEdge(e)) boundary_edges.push_back(topology.EdgeVertices(e));
  }
  const std::vector<Vec3>& x = m.positions;
  std::sort(boundary_edges.begin(), boundary_edges.end(), [&](const Edge& e, const Edge& f) {
    return LowerX(e) < LowerX(f) || (LowerX(e) == LowerX(f) && e < f);
  });
  for (const Edge& e : boundary_edges) longest_boundary_edge = std::max(longest_boundary_edge, (x[e[1]] - x[e[0]]).norm());
}

double InputSurface::LowerX(const Edge& e) const {
  const std::vector<Vec3>& x = mesh->positions;
  return std::min(x[e[0]].x(), x[e[1]].x());
}

std::optional<Vec3> InputSurface::ClosestBoundaryPoint(const Vec3& target, double reach) const {
  const std::vector<Vec3>& x = mesh->positions;
  std::optional<Vec3> best;
  double best_d = reach * reach;
  auto it = std::upper_bound(boundary_edges.begin(), boundary_edges.end(), target.x() + reach,
                             [&](double value, const Edge& e) { return value < LowerX(e); });
  while (it != boundary_edges.begin()) {
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

RemeshParts BaseFaceParts(const InputSurface& surface, const std::vector<uint32_t>& base_to_input,
                          const std::vector<Face>& base_faces) {
  RemeshParts parts;
  if (surface.face_part.empty()) return parts;
  for (const Face& f : base_faces) {
    const uint32_t v = base_to_input[f[0]];
    parts.of_base_face.push_back(surface.face_part[surface.vertex_faces[surface.face_offsets[v]]]);
  }
  return parts;
}

void RefineLevel(const SemiRegularHierarchy& hierarchy, int j, const InputSurface& surface, const RemeshParts& parts,
                 const StencilTable& stencils, std::vector<Vec3>* positions, std::vector<uint32_t>* on_faces,
                 std::vector<VertexKind>* kinds, std::vector<ParamPoint>* params, LevelStats* stats,
                 std::vector<CreasePlace>* creases) {
  *stats = LevelStats();
  std::vector<Vec3> level = *positions;
  const std::vector<uint32_t> level_faces = *on_faces;
  // The refiner reads *creases (level j) while it runs; the odd vertices' places
  // are appended only after.
  remesh_internal::LevelRefiner refiner(hierarchy, j, surface, parts, &level, level_faces, params, creases);
  refiner.Run(stencils, positions, on_faces, kinds, stats);
  if (creases) refiner.AppendCreasePlaces(creases);
  *params = refiner.TakeParams();
}

}  // namespace eqmesh

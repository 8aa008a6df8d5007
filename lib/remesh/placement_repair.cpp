// Placement repair of one refinement (the departure described at
// LevelRefiner::RepairPlacements): folded, sliver or lopsided odd vertices try other
// admissible positions before the next level is pierced from them.
#include <algorithm>
#include <Eigen/Geometry>

#include "remesh/level_refiner.h"
#include "core/parallel_for.h"
#include "remesh/quality_checks.h"

namespace eqmesh::remesh_internal {
namespace {

// Placement repair: sweeps over the suspect vertices, hits tried per vertex,
// and how far from its edge's 3D middle a vertex may sit (0.6: within the
// middle 80 % of the edge).
constexpr int kRepairPasses = 3;
constexpr size_t kRepairCandidates = 8;
constexpr double kMaxLopsidedness = 0.6;
// Slivers are mended where they are local defects: at most this share of a
// level's faces. Mending every level would cost dragon_vrip, whose stalled base
// is a fifth slivers at every level, a sixth of its normal vertices and double
// its refinement time; the bench scans have 0.1-0.5 %.
constexpr double kMaxSliverShare = 0.02;
// Relaxed candidates: how far toward its neighbours' centroid a vertex moves.
constexpr double kRelaxBlends[] = {1.0, 0.5};

}  // namespace

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
  out->on_face = cp.face;
  out->kind = VertexKind::kNonNormal;
  out->needs_forward = false;
  if (!SurfaceParam(k, cp.point, cp.face, cp.barycentric, chart, &out->u)) return false;
  // On 3D-refined levels the diamond is the 3D one and cannot reach a thin
  // part's other side, so the whole diamond is admissible there.
  return fine_ ? InDiamond(out->u, dom_.Sides(k).left_slot) : InKite(out->u, dom_.Sides(k).left_slot);
}

const Vec3& LevelRefiner::FinePosition(uint32_t v) const {
  return v < pos_.size() ? pos_[v] : choice_[v - pos_.size()].position;
}

uint32_t LevelRefiner::FineFace(uint32_t v) const {
  return v < pos_.size() ? on_face_[v] : choice_[v - pos_.size()].on_face;
}

// The fold test searches the input for the triangle closest to a face's
// centroid, 1.2M searches per level on a 100k-face input, most of the fold
// scan's time. On levels finer than the input most faces have all three
// corners on one input triangle, and then the face lies in that triangle, its
// centroid too: the search would find that triangle (short of a tie within
// rounding where another triangle touches it), so the face folds exactly when
// it faces against it. Only the unfolded case is answered here: a face taken
// as unfolded on a guess is a fold no untangling sees, nor the fold retries'
// count (bench/log/2026-12-06-fold-scan-exact.md).
bool LevelRefiner::SurelyUnfolded(const Face& t, const Vec3& normal) const {
  if (!fine_) return false;
  const uint32_t f = FineFace(t[0]);
  if (f == kNoFace || FineFace(t[1]) != f || FineFace(t[2]) != f) return false;
  return normal.dot(s_.face_normals[f]) > 0.0;
}

// A level-(j+1) face folds when it faces away from the input at the closest
// point of its centroid (the remesh check, quality_checks.h); degenerate counts.
// Also returns the face's area times its centroid's squared distance.
bool LevelRefiner::Folded(uint32_t child, double* error) const {
  const Face& t = h_.Faces(j_ + 1)[child];
  const Vec3& a = FinePosition(t[0]);
  const Vec3& b = FinePosition(t[1]);
  const Vec3& c = FinePosition(t[2]);
  const Vec3 n = (b - a).cross(c - a);
  if (!(n.squaredNorm() > 0.0)) return true;
  // Placement scores need the error term, which needs the search.
  if (!error && SurelyUnfolded(t, n)) return false;
  return FacesAwayFromInput(*s_.bvh, *s_.mesh, s_.face_part, parts_.Of(child, j_ + 1), a, b, c, error);
}

// The six level-(j+1) faces around odd vertex k (three children of each side).
std::array<uint32_t, 6> LevelRefiner::FacesAround(uint32_t k) const {
  const EdgeSides& e = dom_.Sides(k);
  const uint32_t l = 4 * e.left, r = 4 * e.right;
  return {l + e.left_slot, l + (e.left_slot + 1) % 3, l + 3, r + e.right_slot, r + (e.right_slot + 1) % 3, r + 3};
}

double LevelRefiner::ChildQuality(uint32_t child) const {
  const Face& t = h_.Faces(j_ + 1)[child];
  return TriangleQuality(FinePosition(t[0]), FinePosition(t[1]), FinePosition(t[2]));
}

// The worst quality of the six faces around odd vertex k, capped at
// the level's sliver bound: placements that keep every face above it tie.
double LevelRefiner::ShapeAround(uint32_t k) const {
  double worst = sliver_quality_;
  for (uint32_t f : FacesAround(k)) worst = std::min(worst, ChildQuality(f));
  return worst;
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
  s.shape = ShapeAround(k);
  return s;
}

// The bound below which this level's child faces count as slivers to mend:
// kSliverQuality, or 0 (none) where more than kMaxSliverShare of them are.
// slivers_in[f]: how many of level-j face f's children are below kSliverQuality.
double LevelRefiner::SliverBound(const std::vector<uint8_t>& slivers_in) const {
  size_t slivers = 0;
  for (uint8_t n : slivers_in) slivers += n;
  const double children = 4.0 * static_cast<double>(slivers_in.size());
  return static_cast<double>(slivers) <= kMaxSliverShare * children ? kSliverQuality : 0.0;
}

// Folds at a level multiply by four at every finer one (their children are
// pierced from folded predictions), and so does a vertex placed next to an end
// of its edge: where the parameterization is compressed the edges around it
// then never shrink (armadillo claws: 0.02 of the diagonal from level 2 to 5).
// So each level is cleaned before the next: an odd vertex of a folded face or a
// sliver (SliverBound), or one within kMaxLopsidedness of an end of its
// edge, tries its other admissible hits, the parametric midpoint and the
// surface point closest to its neighbours' average, and keeps the best
// ScorePlacement (folds, then lopsidedness, then the worst face shape up to
// the sliver bound, then error). Departure from Guskov et al., who take the hit
// closest to the prediction.
std::vector<uint32_t> LevelRefiner::RepairPlacements() {
  const size_t nf = dom_.faces().size();
  std::vector<uint8_t> suspect(choice_.size(), 0);
  std::vector<uint8_t> touched(nf, 0);  // level-j faces whose children may be folded
  std::vector<uint8_t> slivers_in(nf, 0);
  ParallelFor(nf, [&](size_t begin, size_t end, size_t) {
    for (size_t f = begin; f < end; ++f) {
      for (uint32_t c = 0; c < 4; ++c) {
        const uint32_t child = static_cast<uint32_t>(4 * f + c);
        slivers_in[f] += ChildQuality(child) < kSliverQuality;
        if (!Folded(child)) continue;
        touched[f] = 1;
        for (int i = 0; i < 3; ++i) suspect[dom_.EdgeOf(static_cast<uint32_t>(f), i)] = 1;
      }
    }
  });
  sliver_quality_ = SliverBound(slivers_in);
  if (sliver_quality_ > 0.0) {
    for (uint32_t f = 0; f < nf; ++f) {
      if (!slivers_in[f]) continue;
      for (int i = 0; i < 3; ++i) suspect[dom_.EdgeOf(f, i)] = 1;
    }
  }
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
      if (before.folds == 0 && !before.lopsided && before.shape == sliver_quality_) continue;
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
  mid.position = MidpointPosition(k, mid.u, chart, &mid.on_face);
  mid.needs_forward = false;
  options.push_back(mid);
  for (const double blend : kRelaxBlends) {
    EdgeChoice relaxed;
    if (RelaxedChoice(k, blend, chart, &relaxed)) options.push_back(relaxed);
  }
  const EdgeChoice current = choice_[k];
  // A crease point gives way only to fewer folds: its shape and lopsidedness
  // are the crease's.
  const bool on_crease = current.crease.chain != kNoCreaseChain;
  EdgeChoice best = current;
  PlacementScore best_score = before;
  for (const EdgeChoice& o : options) {
    choice_[k] = o;
    if (!ChildrenValid(dom_.Sides(k).left) || !ChildrenValid(dom_.Sides(k).right)) continue;
    const PlacementScore score = ScorePlacement(k);
    if (on_crease && score.folds >= before.folds) continue;
    if (score < best_score) {
      best_score = score;
      best = o;
    }
  }
  choice_[k] = best;
  return best.position != current.position;
}

}  // namespace eqmesh::remesh_internal

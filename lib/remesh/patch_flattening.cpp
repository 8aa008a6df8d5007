// Coarse-patch refills of the folds left after untangling; see patch_flattening.h.
#include "remesh/patch_flattening.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "remesh/quality_checks.h"

namespace eqmesh {
namespace {

// How many levels above the finest a patch may start: 3 refills at most 64
// finest faces per fold (skull_50k: 2, 3 and 4 fix the same folds).
constexpr int kMaxLevelsUp = 3;
// Rounds over the faces a refill changed.
constexpr int kRounds = 3;
// A refill may leave no vertex farther from the input than this share of the
// finest edge length (the patch face's longest edge over 2^levels below it);
// see the header for the measurement.
constexpr double kMaxOffSurfaceShare = 0.5;

// A vertex refinement created inside a patch: level m's odd vertex v, which
// splits edge `edge` of level m.
struct PatchVertex {
  uint32_t v;
  Edge edge;
  int level;
};

class PatchFlattener {
 public:
  PatchFlattener(const SemiRegularHierarchy& h, const InputSurface& s, const RemeshParts& parts,
                 const std::vector<VertexKind>& kinds, const FaceIncidence& finest_faces, StencilCache* stencils,
                 std::vector<Vec3>* pos)
      : h_(h),
        s_(s),
        parts_(parts),
        kinds_(kinds),
        pos_(*pos),
        tiny_(DegenerateDoubleArea(*s.mesh)),
        moved_(pos->size(), 0),
        stencils_(*stencils),
        around_(finest_faces) {}

  // Rounds over the faces that may fold; a refill changes the faces around its
  // vertices, which the next round looks at again.
  void Repair(std::vector<uint32_t> candidates) {
    const int levels = h_.levels();
    for (int round = 0; round < kRounds && !candidates.empty(); ++round) {
      std::vector<uint32_t> next;
      for (uint32_t f : candidates) {
        if (!Folded(levels, f)) continue;
        next.push_back(f);
        for (int up = 1; up <= std::min(kMaxLevelsUp, levels); ++up) {
          std::vector<PatchVertex> refilled;
          if (!TryFlatten(levels - up, f >> (2 * up), &refilled)) continue;
          const std::vector<uint32_t> around = FacesAround(refilled);
          next.insert(next.end(), around.begin(), around.end());
          break;
        }
      }
      std::sort(next.begin(), next.end());
      next.erase(std::unique(next.begin(), next.end()), next.end());
      if (next == candidates) break;
      candidates = std::move(next);
    }
  }

  std::vector<uint8_t> TakeMoved() { return std::move(moved_); }

 private:
  // The remesh's fold test (quality_checks.h) on face f of `level`; degenerate counts.
  bool Folded(int level, uint32_t f) const {
    const Face& t = h_.Faces(level)[f];
    return FoldedOrDegenerate(*s_.bvh, *s_.mesh, s_.face_part, parts_.Of(f, level), pos_[t[0]], pos_[t[1]],
                              pos_[t[2]], tiny_);
  }

  // Vertices created inside face p of `level` or on its edges, coarse to fine,
  // each with the two corners of the edge it splits; false when one lies on a
  // boundary curve (moving it would take it off the input's boundary).
  bool PatchVertices(int level, uint32_t p, std::vector<PatchVertex>* out) const {
    out->clear();
    uint64_t first = p, count = 1;
    for (int m = level; m < h_.levels(); ++m, first *= 4, count *= 4) {
      const std::vector<Face>& faces = h_.Faces(m);
      const std::vector<Face>& children = h_.Faces(m + 1);
      for (uint64_t g = first; g < first + count; ++g) {
        // Child 3 of g is (m_ab, m_bc, m_ca) (semi_regular.h).
        const Face& t = faces[g];
        const Face& mid = children[4 * g + 3];
        const Edge edges[3] = {{t[0], t[1]}, {t[1], t[2]}, {t[2], t[0]}};
        for (int i = 0; i < 3; ++i) {
          if (kinds_[mid[i]] == VertexKind::kBoundary) return false;
          out->push_back({mid[i], edges[i], m});
        }
      }
    }
    return true;
  }

  // Finest faces around the given vertices, each once.
  std::vector<uint32_t> FacesAround(const std::vector<PatchVertex>& verts) const {
    std::vector<uint32_t> faces;
    for (const PatchVertex& p : verts) {
      faces.insert(faces.end(), around_.faces.begin() + around_.offsets[p.v],
                   around_.faces.begin() + around_.offsets[p.v + 1]);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  }

  size_t CountFolded(const std::vector<uint32_t>& faces) const {
    size_t n = 0;
    for (uint32_t f : faces) n += Folded(h_.levels(), f);
    return n;
  }

  // Puts every patch vertex where refinement with zero details would: at its
  // butterfly prediction (smooth, follows the surface's curvature) or at its
  // edge's midpoint (flat: the coarse face's own linear subdivision). Coarse
  // first, so each reads its stencil's already replaced values. Shared edges
  // are listed twice and get the same value both times.
  void Refill(const std::vector<PatchVertex>& verts, bool smooth) {
    for (const PatchVertex& p : verts) {
      if (!smooth) {
        pos_[p.v] = 0.5 * (pos_[p.edge[0]] + pos_[p.edge[1]]);
        continue;
      }
      const StencilTable& st = stencils_.Level(p.level);
      const uint32_t k = p.v - h_.NumVertices(p.level);
      Vec3 x = Vec3::Zero();
      for (uint32_t i = st.offsets[k]; i < st.offsets[k + 1]; ++i) x += st.weights[i] * pos_[st.indices[i]];
      pos_[p.v] = x;
    }
  }

  bool NearInput(const std::vector<PatchVertex>& verts, double reach) const {
    for (const PatchVertex& p : verts) {
      if (!s_.bvh->ClosestPoint(pos_[p.v], reach).found()) return false;
    }
    return true;
  }

  void Restore(const std::vector<PatchVertex>& verts, const std::vector<Vec3>& saved) {
    for (size_t i = 0; i < verts.size(); ++i) pos_[verts[i].v] = saved[i];
  }

  // Refills face p of `level` (smooth, else flat) when that folds fewer of the
  // faces around it.
  bool TryFlatten(int level, uint32_t p, std::vector<PatchVertex>* refilled) {
    if (Folded(level, p)) return false;
    const Face& t = h_.Faces(level)[p];
    const double longest = std::max(
        {(pos_[t[1]] - pos_[t[0]]).norm(), (pos_[t[2]] - pos_[t[1]]).norm(), (pos_[t[0]] - pos_[t[2]]).norm()});
    const double reach = kMaxOffSurfaceShare * std::ldexp(longest, level - h_.levels());
    std::vector<PatchVertex> verts;
    if (!PatchVertices(level, p, &verts)) return false;
    const std::vector<uint32_t> around = FacesAround(verts);
    const size_t before = CountFolded(around);
    std::vector<Vec3> saved;
    for (const PatchVertex& pv : verts) saved.push_back(pos_[pv.v]);
    for (const bool smooth : {true, false}) {
      Refill(verts, smooth);
      if (NearInput(verts, reach) && CountFolded(around) < before) {
        for (const PatchVertex& pv : verts) moved_[pv.v] = 1;
        *refilled = std::move(verts);
        return true;
      }
      Restore(verts, saved);
    }
    return false;
  }

  const SemiRegularHierarchy& h_;
  const InputSurface& s_;
  const RemeshParts& parts_;
  const std::vector<VertexKind>& kinds_;
  std::vector<Vec3>& pos_;
  double tiny_;
  std::vector<uint8_t> moved_;
  StencilCache& stencils_;
  const FaceIncidence& around_;  // of the finest level
};

}  // namespace

std::vector<uint8_t> FlattenFoldedPatches(const SemiRegularHierarchy& hierarchy, const InputSurface& surface,
                                          const RemeshParts& parts, const std::vector<VertexKind>& kinds,
                                          const std::vector<uint32_t>& candidates, const FaceIncidence& finest_faces,
                                          StencilCache* stencils, std::vector<Vec3>* positions) {
  PatchFlattener flattener(hierarchy, surface, parts, kinds, finest_faces, stencils, positions);
  flattener.Repair(candidates);
  return flattener.TakeMoved();
}

}  // namespace eqmesh

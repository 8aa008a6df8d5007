// Level domain and unfolded charts; see level_domain.h (Guskov et al. 2000).
#include "remesh/level_domain.h"

#include <algorithm>
#include <cmath>

namespace eqmesh {

Vec2 ReferenceCorner(int i) {
  static const Vec2 kCorners[3] = {Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.5, 0.8660254037844386)};
  return kCorners[i];
}

Vec2 ToReference2d(const Eigen::Vector3d& u) {
  return u[0] * ReferenceCorner(0) + u[1] * ReferenceCorner(1) + u[2] * ReferenceCorner(2);
}

LevelDomain::LevelDomain(const SemiRegularHierarchy& hierarchy, int j) : faces_(&hierarchy.Faces(j)) {
  const std::vector<Face>& fine = hierarchy.Faces(j + 1);
  const uint32_t base = hierarchy.NumVertices(j);
  sides_.resize(hierarchy.NumOddVertices(j));
  face_edges_.resize(3 * faces_->size());
  for (uint32_t f = 0; f < faces_->size(); ++f) {
    // Child 4f+3 is (m01, m12, m20): the odd vertex of each slot.
    for (int i = 0; i < 3; ++i) {
      const uint32_t k = fine[4 * f + 3][i] - base;
      face_edges_[3 * f + i] = k;
      EdgeSides& s = sides_[k];
      if (s.left == kNoNeighbour) {
        s.left = f;
        s.left_slot = static_cast<uint8_t>(i);
      } else {
        s.right = f;
        s.right_slot = static_cast<uint8_t>(i);
      }
    }
  }
}

uint32_t LevelDomain::Neighbour(uint32_t f, int i) const {
  const EdgeSides& s = sides_[EdgeOf(f, i)];
  return s.left == f && s.left_slot == i ? s.right : s.left;
}

Eigen::Matrix3d LevelDomain::NeighbourCorners(uint32_t f, int i) const {
  const uint32_t g = Neighbour(f, i);
  const Face& ff = (*faces_)[f];
  const Face& gf = (*faces_)[g];
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d a = id.col(i), b = id.col((i + 1) % 3), c = id.col((i + 2) % 3);
  Eigen::Matrix3d out;
  for (int m = 0; m < 3; ++m) {
    if (gf[m] == ff[i]) {
      out.col(m) = a;
    } else if (gf[m] == ff[(i + 1) % 3]) {
      out.col(m) = b;
    } else {
      out.col(m) = a + b - c;
    }
  }
  return out;
}

Eigen::Vector3d LevelDomain::LeftToRight(uint32_t k, const Eigen::Vector3d& u) const {
  const EdgeSides& s = sides_[k];
  const int a = s.left_slot, b = (a + 1) % 3, c = (a + 2) % 3;
  Eigen::Vector3d out;
  // Right face runs b -> a: slot right_slot holds b, the next slot holds a.
  out[s.right_slot] = u[b] + u[c];
  out[(s.right_slot + 1) % 3] = u[a] + u[c];
  out[(s.right_slot + 2) % 3] = -u[c];
  return out;
}

Chart::Chart(const LevelDomain& domain)
    : domain_(domain), slot_(domain.faces().size(), kNoNeighbour) {}

void Chart::Reset(uint32_t root) {
  for (uint32_t f : faces_) slot_[f] = kNoNeighbour;
  faces_.assign(1, root);
  corners_.assign(1, Eigen::Matrix3d::Identity());
  slot_[root] = 0;
  expanded_ = 0;
}

bool Chart::Grow() {
  const size_t before = faces_.size();
  while (faces_.size() == before && expanded_ < faces_.size()) {
    const uint32_t f = faces_[expanded_];
    const Eigen::Matrix3d frame = corners_[expanded_];
    ++expanded_;
    for (int i = 0; i < 3; ++i) {
      const uint32_t g = domain_.Neighbour(f, i);
      if (g == kNoNeighbour || slot_[g] != kNoNeighbour) continue;
      slot_[g] = static_cast<uint32_t>(faces_.size());
      faces_.push_back(g);
      corners_.push_back(frame * domain_.NeighbourCorners(f, i));
    }
  }
  return faces_.size() > before;
}

bool Chart::Map(const ParamPoint& p, Eigen::Vector3d* u, size_t max_faces) {
  while (slot_[p.face] == kNoNeighbour) {
    if (faces_.size() >= max_faces || !Grow()) return false;
  }
  *u = corners_[slot_[p.face]] * Eigen::Vector3d(p.bary[0], p.bary[1], p.bary[2]);
  return true;
}

}  // namespace eqmesh

// Quadric simplification: see quadric_simplification.h.
#include "remesh/quadric_simplification.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mesh/mesh_topology.h"

namespace eqmesh {
namespace {

// A moved face may turn this far at most: beyond it the simplified surface
// starts folding over itself at thin parts, which no quadric sees.
constexpr double kMaxTurnDegrees = 75.0;

struct Collapse {
  double cost;
  uint32_t v, u;  // v is removed, u kept
  uint32_t stamp;  // v's stamp when this was computed
  bool operator>(const Collapse& o) const {
    if (cost != o.cost) return cost > o.cost;
    if (v != o.v) return v > o.v;
    return u > o.u;
  }
};

class Simplifier {
 public:
  explicit Simplifier(const Mesh& mesh)
      : pos_(mesh.positions),
        faces_(mesh.faces),
        face_alive_(mesh.faces.size(), 1),
        around_(mesh.positions.size()),
        quadric_(mesh.positions.size(), Eigen::Matrix4d::Zero()),
        removed_(mesh.positions.size(), 0),
        boundary_(mesh.positions.size(), 0),
        stamp_(mesh.positions.size(), 0),
        min_turn_cos_(std::cos(kMaxTurnDegrees * M_PI / 180.0)) {
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      for (uint32_t v : faces_[f]) around_[v].push_back(f);
      AddPlaneQuadric(f);
    }
    MarkBoundary(mesh);
  }

  void Run(size_t target) {
    size_t alive = pos_.size();
    for (uint32_t v = 0; v < pos_.size(); ++v) PushBest(v);
    while (alive > target && !heap_.empty()) {
      const Collapse c = heap_.top();
      heap_.pop();
      if (removed_[c.v] || c.stamp != stamp_[c.v]) continue;
      if (removed_[c.u] || !Allowed(c.v, c.u)) {
        ++stamp_[c.v];
        PushBest(c.v);
        continue;
      }
      Apply(c.v, c.u);
      --alive;
    }
  }

  Mesh Result() const {
    Mesh out;
    std::vector<uint32_t> index(pos_.size(), 0);
    for (uint32_t v = 0; v < pos_.size(); ++v) {
      if (removed_[v]) continue;
      index[v] = static_cast<uint32_t>(out.positions.size());
      out.positions.push_back(pos_[v]);
    }
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      if (!face_alive_[f]) continue;
      const Face& t = faces_[f];
      out.faces.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
    return out;
  }

 private:
  Vec3 Normal(const Face& t) const { return (pos_[t[1]] - pos_[t[0]]).cross(pos_[t[2]] - pos_[t[0]]); }

  // Area-weighted plane quadric of face f, added to its corners.
  void AddPlaneQuadric(uint32_t f) {
    const Vec3 n2 = Normal(faces_[f]);  // twice the area times the unit normal
    const double len = n2.norm();
    if (!(len > 0.0)) return;
    const Vec3 n = n2 / len;
    const Eigen::Vector4d plane(n.x(), n.y(), n.z(), -n.dot(pos_[faces_[f][0]]));
    const Eigen::Matrix4d q = (0.5 * len) * (plane * plane.transpose());
    for (uint32_t v : faces_[f]) quadric_[v] += q;
  }

  // Vertices on an edge with one face.
  void MarkBoundary(const Mesh& mesh) {
    const MeshTopology topology(mesh);
    for (uint32_t e = 0; e < topology.num_edges(); ++e) {
      if (!topology.IsBoundaryEdge(e)) continue;
      for (uint32_t v : topology.EdgeVertices(e)) boundary_[v] = 1;
    }
  }

  // Sorted neighbours of v.
  std::vector<uint32_t> Neighbours(uint32_t v) const {
    std::vector<uint32_t> out;
    for (uint32_t f : around_[v]) {
      for (uint32_t w : faces_[f]) {
        if (w != v) out.push_back(w);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  static bool Contains(const Face& t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

  // Whether v may collapse into its neighbour u (see the header's departures).
  bool Allowed(uint32_t v, uint32_t u) const {
    if (boundary_[v]) return false;
    std::vector<uint32_t> opposite;
    for (uint32_t f : around_[v]) {
      if (!Contains(faces_[f], u)) continue;
      for (uint32_t w : faces_[f]) {
        if (w != u && w != v) opposite.push_back(w);
      }
    }
    if (opposite.size() != 2) return false;
    const std::vector<uint32_t> nv = Neighbours(v), nu = Neighbours(u);
    std::vector<uint32_t> common;
    std::set_intersection(nv.begin(), nv.end(), nu.begin(), nu.end(), std::back_inserter(common));
    if (common.size() != 2) return false;
    for (uint32_t w : opposite) {
      if (Neighbours(w).size() < 4) return false;
    }
    for (uint32_t f : around_[v]) {
      const Face& t = faces_[f];
      if (Contains(t, u)) continue;
      Face moved = t;
      for (uint32_t& w : moved) {
        if (w == v) w = u;
      }
      const Vec3 before = Normal(t), after = Normal(moved);
      const double a = after.norm(), b = before.norm();
      if (!(a > 1e-12 * b) || after.dot(before) < min_turn_cos_ * a * b) return false;
    }
    return true;
  }

  double Cost(uint32_t v, uint32_t u) const {
    const Eigen::Vector4d x(pos_[u].x(), pos_[u].y(), pos_[u].z(), 1.0);
    return std::max(0.0, x.dot((quadric_[v] + quadric_[u]) * x));
  }

  void PushBest(uint32_t v) {
    if (removed_[v] || boundary_[v]) return;
    bool found = false;
    Collapse best{0.0, v, 0, stamp_[v]};
    for (uint32_t u : Neighbours(v)) {
      const double cost = Cost(v, u);
      if (found && cost >= best.cost) continue;
      if (!Allowed(v, u)) continue;
      best.cost = cost;
      best.u = u;
      found = true;
    }
    if (found) heap_.push(best);
  }

  void Apply(uint32_t v, uint32_t u) {
    for (uint32_t f : around_[v]) {
      Face& t = faces_[f];
      if (Contains(t, u)) {
        face_alive_[f] = 0;
        for (uint32_t w : t) {
          if (w == v) continue;
          auto& list = around_[w];
          const auto at = std::find(list.begin(), list.end(), f);
          if (at != list.end()) list.erase(at);
        }
        continue;
      }
      for (uint32_t& w : t) {
        if (w == v) w = u;
      }
      around_[u].push_back(f);
    }
    around_[v].clear();
    removed_[v] = 1;
    quadric_[u] += quadric_[v];
    // Every collapse candidate that could involve the changed faces: those of u
    // and of its neighbours.
    std::vector<uint32_t> touched = Neighbours(u);
    touched.push_back(u);
    for (uint32_t w : touched) {
      ++stamp_[w];
      PushBest(w);
    }
  }

  const std::vector<Vec3>& pos_;
  std::vector<Face> faces_;
  std::vector<uint8_t> face_alive_;
  std::vector<std::vector<uint32_t>> around_;  // alive faces per vertex
  std::vector<Eigen::Matrix4d> quadric_;
  std::vector<uint8_t> removed_, boundary_;
  std::vector<uint32_t> stamp_;
  double min_turn_cos_;
  std::priority_queue<Collapse, std::vector<Collapse>, std::greater<Collapse>> heap_;
};

}  // namespace

StatusOr<Mesh> SimplifyByQuadrics(const Mesh& mesh, size_t target_vertices) {
  for (const Face& t : mesh.faces) {
    for (uint32_t v : t) {
      if (v >= mesh.positions.size()) return InvalidArgument("face index out of range");
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return InvalidArgument("face with a repeated corner");
  }
  for (const Vec3& p : mesh.positions) {
    if (!p.allFinite()) return InvalidArgument("non-finite position");
  }
  Simplifier simplifier(mesh);
  simplifier.Run(target_vertices);
  return simplifier.Result();
}

}  // namespace eqmesh

// One level of the parameter domain: the level-j faces, their edge adjacency,
// and flat charts made by unfolding neighbouring faces.
//
// Every level-j face has a reference equilateral triangle; a point of the domain is
// (face, barycentric). Unfolding a neighbour across a shared edge reflects its
// reference triangle, which in barycentric terms is the parallelogram rule
// c' = a + b - c, so charts are built from 3x3 matrices alone (Guskov et al. 2000
// work in the diamond of two faces the same way). Around vertices of valence != 6
// the unfolding is not closed; the breadth-first order makes it well defined.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "mesh/semi_regular.h"
#include "remesh/param_point.h"
#include "remesh/ring_flattening.h"

namespace eqmesh {

inline constexpr uint32_t kNoNeighbour = 0xffffffffu;

// 2D corners of the reference triangle.
Vec2 ReferenceCorner(int i);
// 2D point of barycentric (or chart-affine) coordinates u in the reference triangle.
Vec2 ToReference2d(const Eigen::Vector3d& u);

struct EdgeSides {
  uint32_t left = kNoNeighbour;   // face traversing the edge as OddEdge (a -> b)
  uint32_t right = kNoNeighbour;  // face traversing it b -> a; kNoNeighbour on a boundary
  uint8_t left_slot = 0;          // edge is (face[slot], face[slot+1])
  uint8_t right_slot = 0;
};

class LevelDomain {
 public:
  // Needs hierarchy.levels() >= j + 1 (odd vertex ids are read from level j+1).
  LevelDomain(const SemiRegularHierarchy& hierarchy, int j);

  const std::vector<Face>& faces() const { return *faces_; }
  size_t num_edges() const { return sides_.size(); }
  const EdgeSides& Sides(uint32_t k) const { return sides_[k]; }
  // Odd edge index of slot i of face f.
  uint32_t EdgeOf(uint32_t f, int i) const { return face_edges_[3 * f + i]; }
  uint32_t Neighbour(uint32_t f, int i) const;
  // Columns: the corners of the face across slot i of f, in f's chart coordinates.
  Eigen::Matrix3d NeighbourCorners(uint32_t f, int i) const;
  // Converts chart coordinates of the left face of edge k into the right face's.
  Eigen::Vector3d LeftToRight(uint32_t k, const Eigen::Vector3d& u_left) const;

 private:
  const std::vector<Face>* faces_;
  std::vector<EdgeSides> sides_;
  std::vector<uint32_t> face_edges_;
};

// Faces around a root face unfolded into the root's chart, grown breadth first
// on demand. One object per thread, reused for many roots (Reset is O(faces
// touched)), so large charts at fine levels cost only what they visit.
class Chart {
 public:
  explicit Chart(const LevelDomain& domain);
  void Reset(uint32_t root);
  // Chart coordinates of a parameter point; grows the chart up to `max_faces`
  // faces to reach its face, false if that is not enough.
  bool Map(const ParamPoint& p, Eigen::Vector3d* u, size_t max_faces);
  // Adds the next breadth-first face; false when the component is exhausted.
  bool Grow();
  size_t size() const { return faces_.size(); }
  uint32_t face(size_t n) const { return faces_[n]; }

 private:
  const LevelDomain& domain_;
  std::vector<uint32_t> slot_;  // per level face: index into faces_, or kNoNeighbour
  std::vector<uint32_t> faces_;
  std::vector<Eigen::Matrix3d> corners_;
  size_t expanded_ = 0;  // faces_[0, expanded_) have had their neighbours added
};

}  // namespace eqmesh

// TriangleBvh: bounding-volume hierarchy over a triangle mesh for exact
// closest-point and ray queries (the Metro meter, the remesher's piercing and
// projection steps all go through it).
//
// Follows: binned surface-area-heuristic build (Wald, "On fast Construction of
// SAH-based Bounding Volume Hierarchies", RT 2007); closest point on a triangle
// by Voronoi regions (Ericson, Real-Time Collision Detection, §5.1.5); ray /
// triangle by Möller & Trumbore (JGT 1997). Departures are noted in
// triangle_bvh.cpp.
//
// All queries are const and touch no shared mutable state: any number of
// threads may query one TriangleBvh at once.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

inline constexpr uint32_t kNoFace = std::numeric_limits<uint32_t>::max();

struct ClosestPointResult {
  uint32_t face = kNoFace;                  // index into Mesh::faces; kNoFace = none found
  Vec3 point = Vec3::Zero();                // closest point on that face
  std::array<double, 3> barycentric{};      // point = b0*v0 + b1*v1 + b2*v2 of the face
  double squared_distance = std::numeric_limits<double>::infinity();

  bool found() const { return face != kNoFace; }
};

struct RayHit {
  uint32_t face = kNoFace;
  double t = 0.0;                           // hit point = origin + t * dir
  std::array<double, 3> barycentric{};      // as in ClosestPointResult
};

class TriangleBvh {
 public:
  // Validates the mesh (at least one face, indices in range, finite positions
  // on used vertices) and builds the tree. Degenerate (zero-area) faces are
  // kept: they still have a well-defined closest point. The BVH keeps its own
  // copy of the triangle corners, so `mesh` may be destroyed afterwards.
  static StatusOr<TriangleBvh> Build(const Mesh& mesh);

  // Moves the tree onto `mesh`, which must have the faces it was built from
  // (same count, same corners, same order; only the positions may differ):
  // the tree's shape is kept and every box recomputed around the new corners.
  // Every query then answers what it would on a tree built from `mesh` (they
  // are exact whatever the shape; a shape built for nearby positions only
  // keeps them as fast), at a fraction of a build's cost and without its
  // allocations: the meter's series of measurements of one connectivity
  // (surface_distance.h) refits instead of building.
  Status Refit(const Mesh& mesh);

  size_t num_faces() const { return face_ids_.size(); }
  // Box of all triangles (zero box for an empty tree).
  BoundingBox bounds() const;

  // Closest point of the surface to p among points at distance <= max_dist.
  // Returns a result with found() == false when there is none.
  ClosestPointResult ClosestPoint(
      const Vec3& p, double max_dist = std::numeric_limits<double>::infinity()) const;

  // As ClosestPoint, restricted to faces f with filter(f) == true
  // (e.g. "faces owned by this region").
  ClosestPointResult ClosestPointFiltered(
      const Vec3& p, const std::function<bool(uint32_t)>& filter,
      double max_dist = std::numeric_limits<double>::infinity()) const;

  // Every intersection of the segment origin + t*dir, t in [tmin, tmax], with
  // the surface, sorted by t (ties by face). Hits on a shared edge or vertex are
  // reported once: near-identical t values are merged. Rays lying in a
  // triangle's plane do not hit it. `hits` is cleared first.
  void RayAllHits(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                  std::vector<RayHit>* hits) const;

  // The hit with smallest t in [tmin, tmax], if any.
  std::optional<RayHit> RayFirstHit(const Vec3& origin, const Vec3& dir, double tmin,
                                    double tmax) const;
  // As RayFirstHit, among faces f with filter(f) == true.
  std::optional<RayHit> RayFirstHitFiltered(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                                            const std::function<bool(uint32_t)>& filter) const;

  // Internal layout, public only so the build helpers can name it.
  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // bounding box
    uint32_t first;    // leaf: first triangle slot; interior: index of left child (right = first + 1)
    uint32_t count;    // leaf: number of triangles (> 0); interior: 0
  };
  struct Triangle {
    Vec3 v0, v1, v2;
  };

 private:
  // triangles_[i] = the corners of mesh face face_ids_[i].
  void LoadCorners(const Mesh& mesh);
  template <typename Filter>
  ClosestPointResult ClosestPointImpl(const Vec3& p, double max_dist, const Filter& filter) const;
  template <typename Filter>
  std::optional<RayHit> RayFirstHitImpl(const Vec3& origin, const Vec3& dir, double tmin, double tmax,
                                        const Filter& filter) const;
  template <typename Visit>
  void VisitRay(const Vec3& origin, const Vec3& dir, double tmin, double tmax, Visit&& visit) const;

  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;   // in leaf order
  std::vector<uint32_t> face_ids_;    // triangles_[i] is mesh face face_ids_[i]
  double scale_ = 1.0;                // bounding-box diagonal: sets the ray epsilons
};

// Exact closest point to p on triangle (a, b, c); robust on degenerate
// (collinear or coincident) corners. Writes barycentrics of the result.
Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                            std::array<double, 3>* barycentric);

}  // namespace eqmesh

#include "remesh_checks.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "mesh/mesh_topology.h"
#include "mesh/triangle_bvh.h"

namespace eqmesh::testing {

LevelTopology CheckLevelTopology(const Mesh& mesh) {
  LevelTopology out;
  const MeshTopology t(mesh);
  bool ok = t.num_unusable_faces() == 0;
  for (uint32_t e = 0; e < t.num_edges(); ++e) {
    if (t.IsNonManifoldEdge(e) || t.IsInconsistentEdge(e)) ok = false;
    if (t.IsBoundaryEdge(e)) ++out.boundary_edges;
  }
  std::vector<uint32_t> labels;
  size_t used = 0;
  for (uint32_t v = 0; v < t.num_vertices(); ++v) {
    const uint32_t fans = t.VertexFans(v, &labels);
    if (fans > 1) ok = false;
    if (fans > 0) ++used;
  }
  out.manifold = ok;
  out.boundary_loops = t.BoundaryLoops().size();
  out.euler = static_cast<int64_t>(used) - static_cast<int64_t>(t.num_edges()) + static_cast<int64_t>(mesh.faces.size());
  return out;
}

FlipCount CountFlips(const Mesh& remesh, const Mesh& input) {
  FlipCount out;
  auto bvh = TriangleBvh::Build(input);
  if (!bvh.ok()) return out;
  const double diag = BoundingBoxDiagonal(input);
  for (const Face& f : remesh.faces) {
    const Vec3& a = remesh.positions[f[0]];
    const Vec3& b = remesh.positions[f[1]];
    const Vec3& c = remesh.positions[f[2]];
    const Vec3 n = (b - a).cross(c - a);
    if (n.norm() <= 1e-14 * diag * diag) {
      ++out.degenerate;
      continue;
    }
    const ClosestPointResult cp = bvh->ClosestPoint((a + b + c) / 3.0);
    const Face& g = input.faces[cp.face];
    const Vec3 m = (input.positions[g[1]] - input.positions[g[0]]).cross(input.positions[g[2]] - input.positions[g[0]]);
    if (m.dot(n) < 0.0) ++out.flipped;
  }
  return out;
}

double MaxVertexDistance(const Mesh& points, const Mesh& surface) {
  auto bvh = TriangleBvh::Build(surface);
  if (!bvh.ok()) return 1e300;
  double worst = 0.0;
  for (const Vec3& p : points.positions) worst = std::max(worst, std::sqrt(bvh->ClosestPoint(p).squared_distance));
  return worst;
}

double VertexPsnrDb(const Mesh& a, const Mesh& b) {
  auto rms = [](const Mesh& from, const Mesh& to) {
    auto bvh = TriangleBvh::Build(to);
    double sum = 0.0;
    for (const Vec3& p : from.positions) sum += bvh->ClosestPoint(p).squared_distance;
    return std::sqrt(sum / static_cast<double>(from.positions.size()));
  };
  const double d = std::max(rms(a, b), rms(b, a));
  return 20.0 * std::log10(BoundingBoxDiagonal(a) / std::max(d, 1e-300));
}

}  // namespace eqmesh::testing

// Mesh diagnosis on top of MeshTopology.
//
// Topological invariants follow the classic Euler-Poincare bookkeeping for
// triangulated surfaces (e.g. Botsch et al., "Polygon Mesh Processing", 2010,
// ch. 1.3): chi = V - E + F and, for an orientable manifold component with b
// boundary loops, genus = (2 - chi - b) / 2. A pinched vertex is counted once
// per fan, i.e. genus is that of the surface after splitting pinched vertices,
// which is what the repair produces and what the remesher will see.
#include "mesh/diagnose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>

#include <Eigen/Geometry>

namespace eqmesh {
namespace {

using PositionKey = std::array<uint64_t, 3>;

// Exact-equality key: the bit pattern, with -0.0 folded onto +0.0 because they
// compare equal and a welder should treat them as the same point.
PositionKey KeyOf(const Vec3& p) {
  PositionKey key{};
  for (int i = 0; i < 3; ++i) {
    const double x = p[i] == 0.0 ? 0.0 : p[i];
    std::memcpy(&key[i], &x, sizeof(double));
  }
  return key;
}

bool IsFinite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void CountFaces(const Mesh& mesh, const DiagnoseOptions& options, MeshDiagnosis* d) {
  const size_t n = mesh.positions.size();
  for (const Face& f : mesh.faces) {
    if (f[0] >= n || f[1] >= n || f[2] >= n) {
      ++d->invalid_faces;
    } else if (IsDegenerateFace(mesh, f, options.degenerate_area_tolerance)) {
      ++d->degenerate_faces;
    }
  }
}

void CountEdges(const MeshTopology& topo, MeshDiagnosis* d) {
  d->edges = topo.num_edges();
  for (uint32_t e = 0; e < topo.num_edges(); ++e) {
    if (topo.IsBoundaryEdge(e)) ++d->boundary_edges;
    else if (topo.IsNonManifoldEdge(e)) ++d->non_manifold_edges;
    else if (topo.IsInconsistentEdge(e)) ++d->inconsistent_edges;
    ComponentDiagnosis& c = d->component_details[topo.EdgeComponent(e)];
    ++c.edges;
    if (topo.IsBoundaryEdge(e)) ++c.boundary_edges;
    if (topo.IsNonManifoldEdge(e)) ++c.non_manifold_edges;
  }
}

// Counts pinched vertices and, per component, vertex fans (the V of chi).
void CountVertices(const MeshTopology& topo, MeshDiagnosis* d) {
  std::vector<uint32_t> labels;
  const std::vector<uint32_t>& comp = topo.FaceComponents();
  for (uint32_t v = 0; v < topo.num_vertices(); ++v) {
    const uint32_t fans = topo.VertexFans(v, &labels);
    if (fans == 0) continue;
    if (fans > 1) ++d->non_manifold_vertices;
    // Each fan lies in one component (its faces share edges); count it there.
    std::vector<uint8_t> seen(fans, 0);
    const IndexRange star = topo.VertexFaces(v);
    for (size_t i = 0; i < star.size(); ++i) {
      if (seen[labels[i]]) continue;
      seen[labels[i]] = 1;
      ComponentDiagnosis& c = d->component_details[comp[star[i]]];
      ++c.vertices;
      if (fans > 1) ++c.non_manifold_vertices;
    }
  }
}

void FinishComponents(const MeshTopology& topo, MeshDiagnosis* d) {
  for (uint32_t f = 0; f < topo.num_faces(); ++f)
    if (topo.FaceUsable(f)) ++d->component_details[topo.FaceComponents()[f]].faces;
  for (const BoundaryLoop& loop : topo.BoundaryLoops()) {
    ++d->boundary_loops;
    ++d->component_details[loop.component].boundary_loops;
  }
  for (uint32_t e : topo.PlanConsistentOrientation().conflict_edges)
    d->component_details[topo.EdgeComponent(e)].orientable = false;
  for (ComponentDiagnosis& c : d->component_details) {
    c.closed = c.boundary_edges == 0;
    c.euler_characteristic = static_cast<int64_t>(c.vertices) - static_cast<int64_t>(c.edges) +
                             static_cast<int64_t>(c.faces);
    const int64_t twice_genus = 2 - c.euler_characteristic - static_cast<int64_t>(c.boundary_loops);
    // Pinched vertices were split by counting fans; only non-manifold edges
    // leave the genus undefined.
    const bool defined = c.non_manifold_edges == 0 && c.orientable && twice_genus >= 0 && twice_genus % 2 == 0;
    c.genus = defined ? twice_genus / 2 : -1;
    if (c.closed) {
      ++d->closed_components;
      d->closed_genus.push_back(c.genus);
    }
  }
}

// Components when faces touching at a vertex also count as connected: what a
// "pieces" count of a viewer shows, and what MANIFEST.md reports.
size_t CountVertexConnectedComponents(const MeshTopology& topo) {
  std::vector<uint32_t> parent(topo.num_components());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&parent](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  size_t count = topo.num_components();
  for (uint32_t v = 0; v < topo.num_vertices(); ++v) {
    const IndexRange star = topo.VertexFaces(v);
    for (size_t i = 1; i < star.size(); ++i) {
      const uint32_t a = find(topo.FaceComponents()[star[0]]), b = find(topo.FaceComponents()[star[i]]);
      if (a == b) continue;
      parent[std::max(a, b)] = std::min(a, b);
      --count;
    }
  }
  return count;
}

}  // namespace

bool IsDegenerateFace(const Mesh& mesh, const Face& f, double area_tolerance) {
  if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) return true;
  const Vec3& a = mesh.positions[f[0]];
  const Vec3& b = mesh.positions[f[1]];
  const Vec3& c = mesh.positions[f[2]];
  const double twice_area = (b - a).cross(c - a).norm();
  const double longest_sq = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  // Written as !(x > y) so a NaN area counts as degenerate.
  return !(twice_area > area_tolerance * longest_sq);
}

std::vector<uint32_t> FirstVertexWithSamePosition(const std::vector<Vec3>& positions) {
  std::vector<uint32_t> first(positions.size());
  std::iota(first.begin(), first.end(), 0u);
  std::vector<std::pair<PositionKey, uint32_t>> keyed;
  keyed.reserve(positions.size());
  for (uint32_t v = 0; v < positions.size(); ++v)
    if (IsFinite(positions[v])) keyed.emplace_back(KeyOf(positions[v]), v);
  // Integer keys give a strict weak order even where doubles would not.
  std::sort(keyed.begin(), keyed.end());
  for (size_t i = 1; i < keyed.size(); ++i)
    if (keyed[i].first == keyed[i - 1].first) first[keyed[i].second] = first[keyed[i - 1].second];
  return first;
}

size_t CountDuplicatePositions(const std::vector<Vec3>& positions) {
  const std::vector<uint32_t> first = FirstVertexWithSamePosition(positions);
  size_t count = 0;
  for (uint32_t v = 0; v < first.size(); ++v) count += first[v] != v ? 1 : 0;
  return count;
}

MeshDiagnosis Diagnose(const Mesh& mesh, const DiagnoseOptions& options) {
  const MeshTopology topology(mesh);
  return Diagnose(mesh, topology, options);
}

MeshDiagnosis Diagnose(const Mesh& mesh, const MeshTopology& topology, const DiagnoseOptions& options) {
  MeshDiagnosis d;
  d.vertices = mesh.positions.size();
  d.faces = mesh.faces.size();
  d.referenced_vertices = CountReferencedVertices(mesh);
  d.components = topology.num_components();
  d.vertex_connected_components = CountVertexConnectedComponents(topology);
  d.component_details.assign(d.components, ComponentDiagnosis{});
  CountFaces(mesh, options, &d);
  CountEdges(topology, &d);
  CountVertices(topology, &d);
  FinishComponents(topology, &d);
  for (const Vec3& p : mesh.positions) d.non_finite_positions += IsFinite(p) ? 0 : 1;
  d.duplicate_positions = CountDuplicatePositions(mesh.positions);
  d.bbox_diagonal = BoundingBoxDiagonal(mesh);
  return d;
}

}  // namespace eqmesh

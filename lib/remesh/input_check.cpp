// Input validation for the remesher: names the first offending element so a
// user can find it (and points at --repair).
#include "remesh/input_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace eqmesh {
namespace {

std::string EdgeName(const MeshTopology& t, uint32_t e) {
  const Edge& ev = t.EdgeVertices(e);
  return "edge " + std::to_string(ev[0]) + "-" + std::to_string(ev[1]);
}

constexpr const char* kHint = " (run with --repair to fix it)";

// A face listed twice makes its three edges non-manifold; naming the duplicate
// tells the user what is actually wrong (an exporter glitch, not bad topology).
Status CheckNoDuplicateFaces(const Mesh& mesh) {
  std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> keyed(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    std::array<uint32_t, 3> key = mesh.faces[f];
    std::sort(key.begin(), key.end());
    keyed[f] = {key, static_cast<uint32_t>(f)};
  }
  std::sort(keyed.begin(), keyed.end());
  size_t duplicates = 0;
  uint32_t first = 0, original = 0;
  for (size_t i = 1; i < keyed.size(); ++i) {
    if (keyed[i].first == keyed[i - 1].first && keyed[i].first[0] != keyed[i].first[1] &&
        keyed[i].first[1] != keyed[i].first[2] && duplicates++ == 0) {
      first = keyed[i].second;
      original = keyed[i - 1].second;
    }
  }
  if (duplicates == 0) return Status::Ok();
  return InvalidMesh(std::to_string(duplicates) + " duplicate face(s) (same three vertices), first face " +
                     std::to_string(first) + " repeats face " + std::to_string(original) + kHint);
}

}  // namespace

Status CheckRemeshable(const Mesh& mesh, const MeshTopology& topology) {
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces");
  EQMESH_RETURN_IF_ERROR(CheckIndicesAndCoordinates(mesh));
  EQMESH_RETURN_IF_ERROR(CheckNoDuplicateFaces(mesh));
  size_t non_manifold = 0, inconsistent = 0;
  uint32_t first_nm = MeshTopology::kNone, first_inc = MeshTopology::kNone;
  for (uint32_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.IsNonManifoldEdge(e)) {
      if (non_manifold++ == 0) first_nm = e;
    } else if (topology.IsInconsistentEdge(e)) {
      if (inconsistent++ == 0) first_inc = e;
    }
  }
  if (non_manifold > 0) {
    return InvalidMesh(std::to_string(non_manifold) + " non-manifold edge(s) (more than two faces), first " +
                       EdgeName(topology, first_nm) + kHint);
  }
  std::vector<uint32_t> labels;
  size_t pinched = 0;
  uint32_t first_pinched = 0;
  for (uint32_t v = 0; v < topology.num_vertices(); ++v) {
    if (topology.VertexFans(v, &labels) > 1 && pinched++ == 0) first_pinched = v;
  }
  if (pinched > 0) {
    return InvalidMesh(std::to_string(pinched) + " non-manifold (pinched) vertex(es), first vertex " +
                       std::to_string(first_pinched) + kHint);
  }
  if (inconsistent > 0) {
    return InvalidMesh(std::to_string(inconsistent) + " inconsistently oriented edge(s), first " +
                       EdgeName(topology, first_inc) + kHint);
  }
  return Status::Ok();
}

}  // namespace eqmesh

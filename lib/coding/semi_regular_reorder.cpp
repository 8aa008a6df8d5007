#include "coding/semi_regular_reorder.h"

#include <algorithm>
#include <unordered_map>

namespace eqmesh {
namespace {

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// Extends new_to_old over the odd vertices of refinement j -> j+1.
Status MapOddVertices(const SemiRegularHierarchy& old_h, const SemiRegularHierarchy& new_h, int j,
                      std::vector<uint32_t>* new_to_old) {
  std::unordered_map<uint64_t, uint32_t> old_odd;
  old_odd.reserve(old_h.NumOddVertices(j) * 2);
  for (uint32_t k = 0; k < old_h.NumOddVertices(j); ++k) {
    const Edge& e = old_h.OddEdge(j, k);
    old_odd.emplace(EdgeKey(e[0], e[1]), old_h.NumVertices(j) + k);
  }
  for (uint32_t k = 0; k < new_h.NumOddVertices(j); ++k) {
    const Edge& e = new_h.OddEdge(j, k);
    const auto it = old_odd.find(EdgeKey((*new_to_old)[e[0]], (*new_to_old)[e[1]]));
    if (it == old_odd.end()) {
      return InternalError("renumbered base has an edge the original base lacks (level " +
                           std::to_string(j) + ")");
    }
    new_to_old->push_back(it->second);
  }
  return Status::Ok();
}

std::vector<Edge> RenumberedCreases(const std::vector<Edge>& creases, const std::vector<uint32_t>& new_to_old_base) {
  if (creases.empty()) return {};
  std::vector<uint32_t> old_to_new(new_to_old_base.size());
  for (uint32_t i = 0; i < new_to_old_base.size(); ++i) old_to_new[new_to_old_base[i]] = i;
  std::vector<Edge> out;
  out.reserve(creases.size());
  for (const Edge& e : creases) out.push_back({old_to_new[e[0]], old_to_new[e[1]]});
  return out;
}

}  // namespace

StatusOr<SemiRegularMesh> RenumberToBase(const SemiRegularMesh& mesh,
                                         const std::vector<uint32_t>& new_to_old_base,
                                         std::vector<Face> new_base_faces) {
  const SemiRegularHierarchy& old_h = mesh.hierarchy;
  const int levels = old_h.levels();
  if (new_to_old_base.size() != old_h.NumVertices(0) ||
      new_base_faces.size() != old_h.BaseFaces().size()) {
    return InternalError("renumbered base does not match the base counts");
  }
  EQMESH_ASSIGN_OR_RETURN(SemiRegularHierarchy new_h,
                          SemiRegularHierarchy::Build(old_h.NumVertices(0),
                                                      std::move(new_base_faces), levels));
  EQMESH_RETURN_IF_ERROR(new_h.SetBaseCreases(RenumberedCreases(old_h.BaseCreases(), new_to_old_base)));
  std::vector<uint32_t> new_to_old = new_to_old_base;
  new_to_old.reserve(new_h.NumVertices(levels));
  for (int j = 0; j < levels; ++j) {
    EQMESH_RETURN_IF_ERROR(MapOddVertices(old_h, new_h, j, &new_to_old));
  }
  SemiRegularMesh out;
  out.positions.resize(new_to_old.size());
  for (size_t i = 0; i < new_to_old.size(); ++i) out.positions[i] = mesh.positions[new_to_old[i]];
  if (mesh.kinds.size() == mesh.positions.size()) {
    out.kinds.resize(new_to_old.size());
    for (size_t i = 0; i < new_to_old.size(); ++i) out.kinds[i] = mesh.kinds[new_to_old[i]];
  }
  out.hierarchy = std::move(new_h);
  out.kept_exactly = mesh.kept_exactly;
  return out;
}

}  // namespace eqmesh

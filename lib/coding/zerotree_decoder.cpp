// Zerotree level data of the container (see zerotree_decoder.h).
#include "coding/zerotree_decoder.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "coding/level_synthesis.h"
#include "coding/zerotree/zerotree_coder.h"

namespace eqmesh {
namespace {

// Bytes of the payload present in a stream (prefix) of `size` bytes.
size_t PayloadBytes(const StreamInfo& s, size_t size) {
  const uint64_t end = std::min<uint64_t>(size, s.level_offsets[0] + s.level_sizes[0]);
  return end > s.level_offsets[0] ? static_cast<size_t>(end - s.level_offsets[0]) : 0;
}

// The coefficients need the edge tree of all J levels, whatever level is wanted:
// the mesh's own hierarchy when it has them, else *storage.
StatusOr<const SemiRegularHierarchy*> FullHierarchy(const SemiRegularMesh& mesh, int levels,
                                                    SemiRegularHierarchy* storage) {
  if (mesh.hierarchy.levels() == levels) return &mesh.hierarchy;
  auto full = SemiRegularHierarchy::Build(mesh.hierarchy.NumVertices(0), mesh.hierarchy.BaseFaces(), levels,
                                          bitstream::kMaxFinestFaces);
  if (!full.ok()) return full.status().WithContext("eqm base mesh chunk");
  *storage = std::move(full).value();
  EQMESH_RETURN_IF_ERROR(storage->SetBaseCreases(mesh.hierarchy.BaseCreases()));
  return storage;
}

}  // namespace

int ZerotreeLevelsAvailable(const StreamInfo& s, const uint8_t* data, size_t size, int requested) {
  if (requested <= 0 || s.level_offsets.empty() || size <= s.level_offsets[0]) return 0;
  return ZerotreeHeaderComplete(data + s.level_offsets[0], PayloadBytes(s, size)) ? requested : 0;
}

Status DecodeZerotreeLevels(const uint8_t* data, size_t size, const StreamInfo& s, const StreamHeader& h,
                            int levels, SemiRegularMesh* mesh) {
  if (levels == 0) return Status::Ok();
  // The payload must announce the container's J before anything is built for J levels.
  auto announced = ReadZerotreeHeaderLevels(data + s.level_offsets[0], PayloadBytes(s, size));
  if (!announced.ok()) return announced.status().WithContext("eqm zerotree level data");
  if (*announced != s.levels) {
    return CorruptStream("eqm zerotree level data codes " + std::to_string(*announced) +
                         " levels, the header announces " + std::to_string(s.levels));
  }
  while (mesh->hierarchy.levels() < levels) {
    const Status refined = mesh->hierarchy.Refine(bitstream::kMaxFinestFaces);
    if (!refined.ok()) return refined.WithContext("eqm base mesh chunk");
  }
  SemiRegularHierarchy storage;
  EQMESH_ASSIGN_OR_RETURN(const SemiRegularHierarchy* full, FullHierarchy(*mesh, s.levels, &storage));
  auto coeffs = DecodeZerotree(*full, data + s.level_offsets[0], PayloadBytes(s, size), h.quantum,
                               h.tangential_factor());
  if (!coeffs.ok()) return coeffs.status().WithContext("eqm zerotree level data");
  if (coeffs->size() != static_cast<size_t>(s.levels)) {
    return CorruptStream("eqm zerotree level data codes " + std::to_string(coeffs->size()) +
                         " levels, the header announces " + std::to_string(s.levels));
  }
  for (int j = 0; j < levels; ++j) {
    const LevelSynthesis step(mesh->hierarchy, j, h.transform);
    std::vector<Vec3> fine;
    EQMESH_RETURN_IF_ERROR(step.Synthesize(mesh->positions, (*coeffs)[j], &fine));
    EQMESH_RETURN_IF_ERROR(CheckFiniteLevel(fine, j + 1));
    mesh->positions = std::move(fine);
  }
  return Status::Ok();
}

}  // namespace eqmesh

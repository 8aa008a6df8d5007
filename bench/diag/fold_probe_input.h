// What the fold probes (fold_probe, region_probe) both start from: the input,
// its remesh, the input's BVH and one level's faces with their vertex -> face
// incidence, and the fold test and input normals they ask about.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "mesh_io/mesh_io.h"
#include "mesh/semi_regular.h"
#include "mesh_io/semi_regular_io.h"
#include "mesh/triangle_bvh.h"
#include "remesh/quality_checks.h"

namespace eqmesh {

struct FoldProbeInput {
  Mesh input;
  SemiRegularMesh srm;
  TriangleBvh bvh;
  int level = 0;
  std::vector<Vec3> pos;                     // the remesh's positions, free to move
  std::vector<std::vector<uint32_t>> inc;    // vertex -> faces of `level`

  const std::vector<Face>& faces() const { return srm.hierarchy.Faces(level); }

  // Looks at level j from now on (its faces and incidence); false when the
  // remesh has no such level.
  bool UseLevel(int j) {
    if (j < 0 || j > srm.hierarchy.levels()) return false;
    level = j;
    inc.assign(pos.size(), {});
    const std::vector<Face>& f = faces();
    for (uint32_t k = 0; k < f.size(); ++k)
      for (uint32_t v : f[k]) inc[v].push_back(k);
    return true;
  }

  bool Folded(uint32_t f) const {
    const Face& t = faces()[f];
    return FacesAwayFromInput(bvh, input, {}, kAnyPart, pos[t[0]], pos[t[1]], pos[t[2]]);
  }

  // Input face g's normal, scaled by twice its area.
  Vec3 InputFaceNormal(uint32_t g) const {
    const Face& t = input.faces[g];
    const std::vector<Vec3>& x = input.positions;
    return (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
  }

  // Unit normal of the input face closest to p.
  Vec3 InputNormalAt(const Vec3& p) const { return InputFaceNormal(bvh.ClosestPoint(p).face).normalized(); }
};

// Reads INPUT and REMESH.srm and looks at the finest level; nullopt when a file
// does not read.
inline std::optional<FoldProbeInput> LoadFoldProbeInput(const char* input_path, const char* srm_path) {
  auto input = ReadMesh(input_path);
  auto srm = ReadSemiRegular(srm_path);
  if (!input.ok() || !srm.ok()) return std::nullopt;
  auto bvh = TriangleBvh::Build(*input);
  if (!bvh.ok()) return std::nullopt;
  FoldProbeInput p{std::move(*input), std::move(*srm), std::move(*bvh), 0, {}, {}};
  p.pos = p.srm.positions;
  p.UseLevel(p.srm.hierarchy.levels());
  return p;
}

}  // namespace eqmesh

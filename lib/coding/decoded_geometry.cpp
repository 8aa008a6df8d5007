#include "coding/decoded_geometry.h"

#include <utility>

#include "coding/atlas/seam_split.h"
#include "mesh/adaptive_level.h"

namespace eqmesh {

DecodedGeometry ExtractDecodedGeometry(SemiRegularMesh&& decoded) {
  DecodedGeometry out;
  const int level = decoded.hierarchy.levels();
  out.mesh = ExtractLevel(std::move(decoded), level);
  out.normals = UnitVertexNormals(out.mesh);
  return out;
}

DecodedGeometry ExtractDecodedGeometry(const SemiRegularMesh& decoded, const AtlasLayout* atlas) {
  const int level = decoded.hierarchy.levels();
  DecodedGeometry out;
  Mesh welded = ExtractLevel(decoded, level);
  std::vector<Vec3> welded_normals = UnitVertexNormals(welded);
  if (atlas == nullptr) {
    out.mesh = std::move(welded);
    out.normals = std::move(welded_normals);
    return out;
  }
  SeamSplitMesh split = SplitLevelAtSeams(decoded, level, FaceCornerTexCoords(*atlas, AtlasFaces(decoded)));
  out.mesh.positions.resize(split.source_vertex.size());
  out.normals.resize(split.source_vertex.size());
  for (size_t i = 0; i < split.source_vertex.size(); ++i) {
    out.mesh.positions[i] = welded.positions[split.source_vertex[i]];
    out.normals[i] = welded_normals[split.source_vertex[i]];
  }
  out.mesh.faces = std::move(split.faces);
  out.texcoords = std::move(split.texcoords);
  return out;
}

// The finest uniform level of `decoded` within `max_triangles` (0 when none is).
int UniformLevelWithin(const SemiRegularMesh& decoded, uint64_t max_triangles) {
  int level = decoded.hierarchy.levels();
  const uint64_t kept = decoded.kept_exactly.faces.size();
  while (level > 0 && decoded.hierarchy.Faces(level).size() + kept > max_triangles) --level;
  return level;
}

StatusOr<DecodedGeometry> DecodeGeometry(const uint8_t* data, size_t size, const DecodeOptions& options,
                                         DecodeInfo* info) {
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh decoded, DecodeSemiRegular(data, size, options, info));
  EQMESH_ASSIGN_OR_RETURN(const std::optional<AtlasLayout> atlas, DecodeAtlas(data, size, decoded));
  if (!atlas) {
    if (options.max_triangles == 0) return ExtractDecodedGeometry(std::move(decoded));
    DecodedGeometry out;
    out.mesh = ExtractAdaptiveLevel(decoded, options.max_triangles);
    out.normals = UnitVertexNormals(out.mesh);
    return out;
  }
  // Atlas seams are split per uniform level: a budget takes the finest that fits,
  // decoded as such.
  if (options.max_triangles > 0) {
    const int level = UniformLevelWithin(decoded, options.max_triangles);
    if (level < decoded.hierarchy.levels()) {
      DecodeOptions coarser = options;
      coarser.max_level = level;
      coarser.allow_truncated = true;
      EQMESH_ASSIGN_OR_RETURN(decoded, DecodeSemiRegular(data, size, coarser, info));
    }
  }
  return ExtractDecodedGeometry(decoded, &*atlas);
}

}  // namespace eqmesh

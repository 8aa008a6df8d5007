#include "coding/decoded_geometry.h"

#include <utility>

#include "coding/atlas/seam_split.h"

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

StatusOr<DecodedGeometry> DecodeGeometry(const uint8_t* data, size_t size, const DecodeOptions& options,
                                         DecodeInfo* info) {
  EQMESH_ASSIGN_OR_RETURN(SemiRegularMesh decoded, DecodeSemiRegular(data, size, options, info));
  EQMESH_ASSIGN_OR_RETURN(const std::optional<AtlasLayout> atlas, DecodeAtlas(data, size, decoded));
  if (!atlas) return ExtractDecodedGeometry(std::move(decoded));
  return ExtractDecodedGeometry(decoded, &*atlas);
}

}  // namespace eqmesh

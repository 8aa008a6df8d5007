#include "gltf/stream_decoder.h"

#if EQMESH_HAVE_DECODER
#include "coding/atlas/seam_split.h"
#include "coding/decoder.h"
#endif

#include "gltf/accessor_io.h"

namespace eqmesh::gltf {

#if EQMESH_HAVE_DECODER

namespace {

std::vector<uint64_t> ChunkLengths(const StreamInfo& info) {
  std::vector<uint64_t> lengths;
  lengths.push_back(info.header_size + info.base_size + info.kept_size + info.atlas_size);
  lengths.insert(lengths.end(), info.level_sizes.begin(), info.level_sizes.end());
  return lengths;
}

// The welded level's normals (the spec's rule) follow each vertex to its copies.
void SetSplitGeometry(const SemiRegularMesh& decoded, const AtlasLayout& atlas, DecodedStream* out) {
  const int level = decoded.hierarchy.levels();
  const Mesh welded = ExtractLevel(decoded, level);
  const std::vector<Vec3> welded_normals = UnitVertexNormals(welded);
  SeamSplitMesh split = SplitLevelAtSeams(decoded, level, FaceCornerTexCoords(atlas, AtlasFaces(decoded)));
  out->mesh.positions.resize(split.source_vertex.size());
  out->normals.resize(split.source_vertex.size());
  for (size_t i = 0; i < split.source_vertex.size(); ++i) {
    out->mesh.positions[i] = welded.positions[split.source_vertex[i]];
    out->normals[i] = welded_normals[split.source_vertex[i]];
  }
  out->mesh.faces = std::move(split.faces);
  out->texcoords = std::move(split.texcoords);
}

}  // namespace

StreamDecoderFn EqmeshStreamDecoder() {
  return [](const uint8_t* data, size_t size, int max_level) -> StatusOr<DecodedStream> {
    DecodeOptions options;
    options.max_level = max_level;
    // A loader asking for level K passes only the bytes up to the end of chunk K.
    options.allow_truncated = max_level >= 0;
    DecodeInfo info;
    DecodedStream out;
    EQMESH_ASSIGN_OR_RETURN(const SemiRegularMesh decoded, DecodeSemiRegular(data, size, options, &info));
    EQMESH_ASSIGN_OR_RETURN(const std::optional<AtlasLayout> atlas, DecodeAtlas(data, size, decoded));
    if (atlas) {
      SetSplitGeometry(decoded, *atlas, &out);
    } else {
      out.mesh = ExtractLevel(decoded, decoded.hierarchy.levels());
      out.normals = UnitVertexNormals(out.mesh);
    }
    out.stream_levels = info.levels_in_stream;
    out.level_decoded = info.levels_decoded;
    out.chunk_lengths = ChunkLengths(info.stream);
    out.coder = static_cast<int>(info.stream.coder);
    return out;
  };
}

StreamLayoutFn EqmeshStreamLayout() {
  return [](const uint8_t* data, size_t size) -> StatusOr<std::vector<uint64_t>> {
    EQMESH_ASSIGN_OR_RETURN(const StreamInfo info, ReadStreamInfo(data, size));
    return ChunkLengths(info);
  };
}

#else

StreamDecoderFn EqmeshStreamDecoder() {
  return [](const uint8_t*, size_t, int) -> StatusOr<DecodedStream> {
    return UnsupportedFeature("this build has no eqmesh decoder");
  };
}

StreamLayoutFn EqmeshStreamLayout() {
  return [](const uint8_t*, size_t) -> StatusOr<std::vector<uint64_t>> {
    return UnsupportedFeature("this build has no eqmesh decoder");
  };
}

#endif

}  // namespace eqmesh::gltf

#include "gltf/stream_decoder.h"

#if EQMESH_HAVE_DECODER
#include "coding/decoded_geometry.h"
#include "coding/decoder.h"
#endif

namespace eqmesh::gltf {

#if EQMESH_HAVE_DECODER

namespace {

std::vector<uint64_t> ChunkLengths(const StreamInfo& info) {
  std::vector<uint64_t> lengths;
  lengths.push_back(info.header_size + info.base_size + info.kept_size + info.atlas_size + info.crease_size);
  lengths.insert(lengths.end(), info.level_sizes.begin(), info.level_sizes.end());
  return lengths;
}

}  // namespace

StreamDecoderFn EqmeshStreamDecoder() {
  return [](const uint8_t* data, size_t size, int max_level, uint64_t max_triangles) -> StatusOr<DecodedStream> {
    DecodeOptions options;
    options.max_level = max_level;
    options.max_triangles = max_triangles;
    // A loader asking for level K passes only the bytes up to the end of chunk K.
    options.allow_truncated = max_level >= 0;
    DecodeInfo info;
    DecodedStream out;
    EQMESH_ASSIGN_OR_RETURN(DecodedGeometry geometry, DecodeGeometry(data, size, options, &info));
    out.mesh = std::move(geometry.mesh);
    out.normals = std::move(geometry.normals);
    out.texcoords = std::move(geometry.texcoords);
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

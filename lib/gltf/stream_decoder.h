// The loader's view of a compressed stream: bytes in, mesh and chunk layout out.
// The loader takes the decoder as a function so the glTF container logic can be
// tested with a stand-in stream; the default is the eqmesh codec (lib/coding).
#pragma once

#include <cstddef>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh::gltf {

struct DecodedStream {
  // The decoded level, kept components appended; with an atlas, split at its seams
  // (see coding/atlas/seam_split.h).
  Mesh mesh;
  std::vector<Vec3> normals;  // unit, per vertex of `mesh`, from the welded level; empty: the spec rule on `mesh`
  std::vector<std::array<float, 2>> texcoords;  // TEXCOORD_0; empty without an atlas
  int stream_levels = 0;               // J as the stream header states it
  int level_decoded = 0;               // K
  std::vector<uint64_t> chunk_lengths; // J + 1: header+base+kept, then each level chunk
  // The header's coder id (ext_spec A.2 field 5): coder 1 (zerotree) carries every
  // level in chunk 1 and leaves chunks 2..J empty, which validity rule 10 allows
  // for that coder only.
  int coder = 0;
};

// Decodes `size` bytes (the stream, or a prefix reaching the end of level
// `max_level`'s chunk) up to `max_level` (-1: all levels), within `max_triangles`
// (0: no budget; DecodeOptions::max_triangles).
using StreamDecoderFn =
    std::function<StatusOr<DecodedStream>(const uint8_t* data, size_t size, int max_level, uint64_t max_triangles)>;

// Chunk lengths of the stream whose header starts `data` (`size` may be a prefix):
// what levelByteRanges must restate.
using StreamLayoutFn = std::function<StatusOr<std::vector<uint64_t>>(const uint8_t* data, size_t size)>;

// The eqmesh codec, or a decoder that fails with kUnsupportedFeature when this build
// has no eqmesh_decoder.
StreamDecoderFn EqmeshStreamDecoder();
StreamLayoutFn EqmeshStreamLayout();

}  // namespace eqmesh::gltf

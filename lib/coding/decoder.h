// eqmesh decoder: .eqm stream -> mesh at any level of detail.
//
// Safe for untrusted input: every read is bounds-checked, declared counts are
// checked against the remaining bytes and against fixed limits
// (bitstream_shared.h) before anything is allocated; malformed input gives a
// non-OK Status (kCorruptStream, kUnsupportedVersion, kUnsupportedFeature,
// kResourceLimit), never a crash or hang. A valid but hostile stream can still
// decode to garbage geometry (finite values, bounded size).
//
// Bounded allocation. For a stream (or prefix) of S bytes, no single allocation
// exceeds DecodeAllocationBound(S) = kDecodeAllocSlackBytes +
// kDecodeAllocPerStreamByte * S before the decoder has read the bytes that justify
// it:
//  * the header's level count and chunk sizes are checked against S and the limits
//    of bitstream_shared.h before anything is built from them;
//  * the base and kept chunks are Draco buffers, whose connectivity header counts
//    Draco 1.5 allocates for unchecked: eqmesh reads them first and refuses more
//    than 2^17 + 64 faces or vertices per chunk byte (base_mesh_decoder.h; the slack
//    covers what Draco then allocates, and its fixed-size tables), and checks
//    Draco's output against kMaxBaseVertices / kMaxFinestFaces;
//  * the hierarchy is built one level at a time: level j+1 (4x the faces of level
//    j) only once level j has decoded, and level j's coefficient storage only once
//    chunk j declares exactly that level's coefficient count (EQ: its count field;
//    uniform: at most 256 coefficients per chunk byte, what the range coder can
//    hold; zerotree: the payload header repeats the header's level count J).
// So a header that claims more levels, larger chunks or a bigger base than its
// bytes hold is refused within this bound (tests/fuzz_regressions/
// decode_alloc_bound_test.cpp measures it). What a VALID stream decodes to is not
// proportional to S: a level whose coefficients all quantize to zero costs about a
// dozen bytes, so a few hundred bytes can legitimately describe the format limit
// of kMaxFinestFaces faces (a few GB of working memory). Callers decoding untrusted
// streams in little memory cap DecodeOptions::max_level.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "coding/atlas/atlas_layout.h"
#include "coding/bitstream_shared.h"
#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// The header and the byte range of every chunk (what a glTF loader needs to fetch
// a coarse level first). Offsets are from the start of the stream.
struct StreamInfo {
  uint8_t version_major = 0;
  uint8_t version_minor = 0;
  bitstream::TransformId transform = bitstream::TransformId::kUnlifted;
  bitstream::CoderId coder = bitstream::CoderId::kEq;
  int levels = 0;  // refinement levels in the stream (level count J)
  double lambda = 0;
  double tangential_factor = 0;
  double quantum = 0;
  bool has_kept_exactly = false;
  bool has_compact_base = false;  // base chunk is a compact chunk (1.2), not Draco
  bool has_compact_kept = false;  // kept chunk is a compact chunk (1.5), not Draco
  bool has_positions_after = false;  // compact chunks in the positions-after layout (1.6)
  bool has_tangential_context = false;  // EQ tangential parts context-modelled (1.3)
  bool has_atlas = false;               // an atlas chunk gives TEXCOORD_0 (1.4)
  uint64_t header_size = 0;
  uint64_t base_offset = 0, base_size = 0;
  uint64_t kept_offset = 0, kept_size = 0;  // size 0 when absent
  uint64_t atlas_offset = 0, atlas_size = 0;  // size 0 when absent
  bool has_creases = false;                   // a crease chunk tags base edges (1.8)
  uint64_t crease_offset = 0, crease_size = 0;  // size 0 when absent
  std::vector<uint64_t> level_offsets;      // chunk of refinement j -> j+1
  std::vector<uint64_t> level_sizes;
  uint64_t total_size = 0;                  // bytes of the complete stream
  // Bytes needed to decode up to level k (k = 0..levels): a progressive loader
  // fetches the first prefix_size[k] bytes to show level k.
  std::vector<uint64_t> prefix_size;
};

// Measured (decode_alloc_bound_test): Draco's largest allocation for a hostile base
// chunk is 80 KB, 1.7 MB for one declaring the most faces the resource rule allows;
// a uniform-coded filler level 1.6 KB per stream byte. The slack also leaves room
// for Draco's rANS look-up tables (up to 4 MB).
inline constexpr uint64_t kDecodeAllocSlackBytes = uint64_t{8} << 20;
inline constexpr uint64_t kDecodeAllocPerStreamByte = 4096;
constexpr uint64_t DecodeAllocationBound(uint64_t stream_bytes) {
  return kDecodeAllocSlackBytes + kDecodeAllocPerStreamByte * stream_bytes;
}

// Parses the header only; `size` may be a prefix of the stream (>= header).
StatusOr<StreamInfo> ReadStreamInfo(const uint8_t* data, size_t size);

struct DecodeOptions {
  // Finest level to reconstruct: -1 = all; larger than the stream's level count
  // means all (DecodeInfo::levels_decoded says what was decoded).
  int max_level = -1;
  // A stream prefix that ends inside a level chunk: false -> kCorruptStream;
  // true -> decode the levels whose chunks are complete. A prefix that ends before
  // the base (and kept) chunks end is always an error.
  bool allow_truncated = false;
  // Triangle budget of Decode's mesh (0: none). Levels whose uniform mesh is
  // heavier are cut down adaptively: faces split where the surface needs them,
  // closed conformingly (mesh/adaptive_level.h).
  uint64_t max_triangles = 0;
};

struct DecodeInfo {
  StreamInfo stream;
  int levels_in_stream = 0;
  int levels_decoded = 0;   // the returned mesh is this level
  bool truncated = false;   // the input was a strict prefix of the stream
};

// Full-resolution (or max_level) mesh: the semi-regular level with the
// kept-exactly components appended.
StatusOr<Mesh> Decode(const uint8_t* data, size_t size, const DecodeOptions& options = {},
                      DecodeInfo* info = nullptr);

// Same, keeping the semi-regular structure (hierarchy built to levels_decoded;
// kinds empty).
StatusOr<SemiRegularMesh> DecodeSemiRegular(const uint8_t* data, size_t size,
                                            const DecodeOptions& options = {},
                                            DecodeInfo* info = nullptr);

// The faces an atlas lays out: the base faces, then the kept-exactly faces with
// their vertex indices moved past the base vertices.
std::vector<Face> AtlasFaces(const SemiRegularMesh& mesh);

// The stream's texture atlas, validated against `mesh` (its DecodeSemiRegular
// result, at any level); empty when the stream has none. With
// FaceCornerTexCoords and SplitLevelAtSeams (coding/atlas/) it gives TEXCOORD_0.
StatusOr<std::optional<AtlasLayout>> DecodeAtlas(const uint8_t* data, size_t size, const SemiRegularMesh& mesh);

}  // namespace eqmesh

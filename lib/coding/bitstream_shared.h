// Every identifier of the .eqm bitstream, in one place (Draco's compression_shared.h
// pattern). The values are part of the format: NEVER renumber or reuse one; add new
// values at the end and bump kVersionMinor (compatible addition) or kVersionMajor.
//
// Stream layout, version 1.4 (all multi-byte integers little endian; "varint" is
// unsigned LEB128, "svarint" zig-zag LEB128; ext_spec/ restates this normatively):
//
//   magic            4 bytes  "EQMS"
//   version_major    u8       kVersionMajor
//   version_minor    u8       kVersionMinor
//   transform        u8       TransformId
//   coder            u8       CoderId
//   levels           u8       J, number of refinement levels, <= kMaxLevels
//   flags            u8       HeaderFlag bits; unknown bits set -> corrupt
//   lambda_code      svarint  lambda = 2^(lambda_code / kLogCodeScale), per squared
//                             quantum: level chunks minimise R[bits] + lambda*D/q0^2
//   tangential_code  svarint  tangential factor = 2^(tangential_code / kLogCodeScale)
//   quantum          f32      q0 > 0, world units: coefficient unit of the level coder
//   base_size        varint   bytes of the base-mesh chunk (> 0)
//   kept_size        varint   only with kHasKeptExactly: bytes of the kept chunk (> 0)
//   atlas_size       varint   only with kHasAtlas: bytes of the atlas chunk (> 0)
//   crease_size      varint   only with kCreaseEdges: bytes of the crease chunk (> 0)
//   level_size[J]    varint   bytes of level chunk j = 0..J-1 (refinement j -> j+1)
//   -- end of header; chunks follow back to back, no padding, nothing after --
//   base chunk       the base connectivity and the level-0 scaling values
//                    (positions for unlifted, lifted scaling values for lifted),
//                    quantized to the depth the encoder chose: with kCompactBase
//                    (since 1.2) a compact chunk (coding/compact_base/), else a
//                    Draco mesh buffer. Its vertex order defines base vertex numbering.
//   kept chunk       Draco mesh buffer of SemiRegularMesh::kept_exactly.
//   atlas chunk      (since 1.4) the texture atlas: a square cell per base face, or
//                    per pair of base faces across an edge, from which every level's
//                    TEXCOORD_0 follows (coding/atlas/atlas_layout.h).
//   crease chunk     (since 1.8) the base edges tagged as creases, which every
//                    level's butterfly stencils follow (coding/crease_chunk.h).
//   level chunks     opaque to the container; for kCoderEq one EqLevel chunk each
//                    (lib/coding/eq), decoded against the hierarchy level layout,
//                    with context-modelled tangential parts when kTangentialContext;
//                    for kZerotree (since 1.1) chunk 0 is ONE embedded payload of
//                    all levels (zerotree_decoder.h) and chunks 1..J-1 are empty.
//
// A reader that stops after level chunk k has a complete level-(k+1) mesh: the level
// table lets it know every chunk's byte range from the header alone. (Zerotree:
// any prefix of the payload gives every level at a coarser quality.)
#pragma once

#include <cstdint>

namespace eqmesh::bitstream {

constexpr uint8_t kMagic[4] = {'E', 'Q', 'M', 'S'};
constexpr uint8_t kVersionMajor = 1;
constexpr uint8_t kVersionMinor = 8;  // 1.1: coder 1 (zerotree); 1.2: kCompactBase;
                                      // 1.3: kTangentialContext; 1.4: kHasAtlas;
                                      // 1.5: kCompactKept; 1.6: kCompactPositionsAfter;
                                      // 1.7: the parallelogram choice (compact_positions.h);
                                      // 1.8: kCreaseEdges (crease_chunk.h)
// A stream carries the lowest minor version that has every feature it uses, so an
// optional feature leaves the streams without it byte-identical: 1.3 without an
// atlas or a compact kept chunk, 1.4 with an atlas, 1.5 with a compact kept chunk,
// 1.6 with compact chunks in the positions-after layout (the encoder picks the
// layout per stream, with the base's depth: the older one wins on small bases), 1.7
// (flag kParallelogramChoice) with a compact base chunk whose mode byte is
// kGridChoiceModeByte, 1.8 with a crease chunk.
constexpr uint8_t kVersionMinorWithoutAtlas = 3;
constexpr uint8_t kVersionMinorAtlas = 4;
constexpr uint8_t kVersionMinorCompactKept = 5;
constexpr uint8_t kVersionMinorPositionsAfter = 6;
constexpr uint8_t kVersionMinorParallelogramChoice = 7;
constexpr uint8_t kVersionMinorCreaseEdges = 8;

// Wavelet transform the level chunks are expressed in. Pinned values.
enum class TransformId : uint8_t {
  kUnlifted = 0,  // interpolating butterfly: detail = position - prediction
  kLifted = 1,    // butterfly predict + update lifting step (lib/wavelet/transform.h)
};

// Coefficient coder of the level chunks. Pinned values.
enum class CoderId : uint8_t {
  kEq = 0,        // Estimation-Quantization coder (Lavu, Choi, Baraniuk 2003)
  kZerotree = 1,  // zerotree coder (Khodakovsky, Guskov; PGC), since 1.1
  kUniform = 2,   // baseline: uniform scalar quantizer + adaptive Exp-Golomb (level_decoder.h)
};
constexpr uint8_t kMaxCoderId = 2;

// Bits of the header's flags byte. Pinned values.
enum HeaderFlag : uint8_t {
  kHasKeptExactly = 1u << 0,  // a kept-exactly chunk follows the base chunk
  kCompactBase = 1u << 1,     // the base chunk is a compact chunk, not Draco (1.2)
  kTangentialContext = 1u << 2,  // EQ chunks context-model tangential parts (1.3; coder kEq only)
  kHasAtlas = 1u << 3,           // an atlas chunk follows the kept (or base) chunk (1.4)
  kCompactKept = 1u << 4,        // the kept chunk is a compact chunk, not Draco (1.5)
  kCompactPositionsAfter = 1u << 5,  // compact chunks code positions after connectivity (1.6)
  kParallelogramChoice = 1u << 6,    // the compact base chunk's axis grid has the parallelogram choice (1.7)
  kCreaseEdges = 1u << 7,            // a crease chunk tags base edges as creases (1.8; levels > 0)
};
constexpr uint8_t kKnownFlags = kHasKeptExactly | kCompactBase | kTangentialContext | kHasAtlas | kCompactKept |
                                kCompactPositionsAfter | kParallelogramChoice | kCreaseEdges;

// lambda and the tangential factor travel as log2 codes in 1/kLogCodeScale steps;
// the encoder codes with the value the decoder will rebuild from the code.
// Same 1/16-octave steps as the EQ coder's own lambda code (coding/eq/eq_model.h).
constexpr double kLogCodeScale = 16.0;
constexpr int64_t kMaxLogCode = 16 * 200;  // |log2| <= 200: far beyond any sane value

// Limits the decoder enforces before allocating (hostile-stream safety).
constexpr int kMaxLevels = 12;
constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 32;
constexpr uint32_t kMaxBaseVertices = 1u << 20;
constexpr uint64_t kMaxFinestFaces = uint64_t{1} << 24;
// Atlas grid side in texels (the largest texture WebGL 2 guarantees is 2048; GPUs
// commonly take 16384).
constexpr uint32_t kMaxAtlasSide = 16384;
// Texels inside each atlas cell's border, kept free of the triangles it holds.
constexpr uint32_t kMaxAtlasGutter = 255;

// Depths of the base chunk the encoder tries, and the depth of the kept chunk, compact
// or Draco (listed here because its precision is a format promise: "kept exactly" to
// this many bits).
constexpr int kBaseMinBits = 8;
constexpr int kBaseMaxBits = 20;
constexpr int kKeptBits = 20;

// The encoder's quantum q0 = bbox diagonal * 2^-kQuantumLog2 (the decoder reads q0).
constexpr int kQuantumLog2 = 16;

}  // namespace eqmesh::bitstream

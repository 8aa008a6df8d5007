// A stand-in for the eqmesh codec with the same container-visible behaviour, so the
// glTF converter and loader can be tested without remeshing or entropy coding:
//
//   chunk 0: "FAKE" | u8 J | u32 V | u32 F | V x 3 f64 positions | F x 3 u32 faces
//   chunk j (1..J): "L" | u8 j | (j + 2) bytes 0xAB   (length j + 4)
//
// Decoding builds the real semi-regular hierarchy (lib/mesh/semi_regular.h) of the
// base to the requested level and places odd vertices at edge midpoints, so vertex
// counts per level are those of the real format. Every byte is checked: any change
// is a corrupt-stream error.
#pragma once

#include <cstdint>
#include <vector>

#include "gltf/compress_primitives.h"
#include "gltf/stream_decoder.h"
#include "mesh/mesh.h"

namespace eqmesh::testing {

std::vector<uint8_t> MakeFakeStream(const Mesh& base, int levels);

// StreamDecoderFn over the fake format.
// (The fake format has no budget: max_triangles is ignored.)
StatusOr<gltf::DecodedStream> DecodeFakeStream(const uint8_t* data, size_t size, int max_level,
                                               uint64_t max_triangles = 0);

// GeometryCompressor: the input mesh becomes the base, refined `levels` times.
gltf::GeometryCompressor FakeCompressor(int levels);

}  // namespace eqmesh::testing

// What every loader makes of a decoded level (the glTF loader, the C API, the
// WebAssembly module): positions, unit normals by ext_spec's rule
// (UnitVertexNormals over the welded level), indices, and with an atlas the vertices split at its
// seams with TEXCOORD_0 (ext_spec B.7).
#pragma once

#include <array>
#include <vector>

#include "coding/atlas/atlas_layout.h"
#include "coding/decoder.h"
#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct DecodedGeometry {
  Mesh mesh;                                    // split at the atlas seams, if any
  std::vector<Vec3> normals;                    // unit, per vertex of mesh
  std::vector<std::array<float, 2>> texcoords;  // per vertex of mesh; empty without an atlas
};

// The finest decoded level of `decoded` (kept components appended); `atlas` null
// for a stream without one.
DecodedGeometry ExtractDecodedGeometry(const SemiRegularMesh& decoded, const AtlasLayout* atlas);
// The same without an atlas, for a mesh the caller is done with: its finest level
// is moved, not copied (a loader's peak memory is then one level less).
DecodedGeometry ExtractDecodedGeometry(SemiRegularMesh&& decoded);

// DecodeSemiRegular, DecodeAtlas and ExtractDecodedGeometry in one: what a loader
// makes of `size` bytes of a stream. options.max_triangles cuts the result down
// adaptively (mesh/adaptive_level.h); with an atlas, to the finest uniform level
// within it (seams are split per level).
StatusOr<DecodedGeometry> DecodeGeometry(const uint8_t* data, size_t size, const DecodeOptions& options,
                                         DecodeInfo* info);

}  // namespace eqmesh

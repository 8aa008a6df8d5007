// The texture half of compressing a textured (or vertex-coloured) primitive: an
// atlas laid out on the decoded remesh joins the stream (TEXCOORD_0 then costs a
// few bytes per base face), and every texture the material samples is painted into
// it from the input (lib/texture/), COLOR_0 multiplied into the base colour.
// A normal map is re-expressed in the decoded surface's tangent frames.
// Re-encoded in its input format: JPEG at the input's estimated quality, PNG
// losslessly; a base colour made of COLOR_0 alone as JPEG.
#pragma once

#include <cstdint>

#include "core/status.h"
#include "gltf/compress_primitives.h"

namespace eqmesh::gltf {

// The primitive's mesh with vertices at bitwise-identical positions merged (a
// textured mesh is split along its UV seams; the remesher needs the surface);
// welded_index, when given, receives each vertex's welded index.
Mesh WeldedByPosition(const Mesh& mesh, std::vector<uint32_t>* welded_index = nullptr);

// `out` holds the primitive's encoded stream (no atlas yet). Adds the atlas to it,
// replaces chunk_lengths, decoded, normals and texcoords by the textured decode,
// and fills `textures`. texture_size: the atlas images' side (0: each input
// texture's own size, the grid the largest of them).
Status AddAtlasAndTextures(const PrimitiveGeometry& input, uint32_t texture_size, CompressedGeometry* out);

}  // namespace eqmesh::gltf

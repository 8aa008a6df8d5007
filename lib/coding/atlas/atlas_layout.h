// The texture atlas of a normal-mesh stream (chunk since 1.4): where each base face
// (and each kept-exactly face) lies in texture space. Every vertex of a remeshed
// level has exact dyadic barycentric coordinates in its base face, so this table
// alone gives TEXCOORD_0 at every level: the atlas costs a few bytes per base face,
// not a coordinate pair per vertex (the re-parameterization idea of MPEG V-DMC,
// with the chart layout taken from the normal mesh's own base domain).
//
// Normative rule (ext_spec Appendix B.6). Atlas faces are the base faces [0, F) then
// the kept-exactly faces [F, F + K), in the decoder's order. A cell is a square of
// `side` texels at (x, y) of a width x height grid (x right, y down from the image's
// top-left corner). Inside it, lo = (x + g, y + g) and hi = (x + side - g,
// y + side - g), g the chunk's gutter. Face a's corners e, e+1, e+2 (mod 3) go to
// (hi.x, lo.y), (lo.x, hi.y), (lo.x, lo.y): a right isosceles triangle whose
// hypotenuse is face a's edge from corner e to corner e+1. A paired cell also holds
// face b, the face across that edge: the edge's ends keep their texture
// coordinates (no seam across the diagonal) and b's third corner goes to
// (hi.x, hi.y). Texture coordinates are the texel positions divided by width and
// height.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct AtlasCell {
  uint32_t face_a = 0;
  uint32_t face_b = 0;  // only when paired
  uint8_t edge = 0;     // face a's corner where the hypotenuse starts (0..2)
  bool paired = false;
  uint32_t x = 0, y = 0, side = 0;
};

struct AtlasLayout {
  uint32_t width = 0, height = 0;  // texel grid the cells are placed in
  uint32_t gutter = 0;             // texels between a cell's border and its triangles
  std::vector<AtlasCell> cells;
};

using TexCoord = std::array<double, 2>;
using FaceTexCoords = std::array<TexCoord, 3>;  // per face corner, in texture units [0, 1]

std::vector<uint8_t> WriteAtlasChunk(const AtlasLayout& atlas);

// Parses and validates a chunk against the faces it lays out (base faces then
// kept faces, kept vertex indices offset past the base vertices so the two sets
// share no edge): every face in exactly one cell, cells inside the grid and large
// enough for the gutter, a paired face_b across face a's hypotenuse.
StatusOr<AtlasLayout> ReadAtlasChunk(const uint8_t* data, size_t size, const std::vector<Face>& faces);

// Corner texture coordinates of every face, by the rule above (layout validated).
std::vector<FaceTexCoords> FaceCornerTexCoords(const AtlasLayout& atlas, const std::vector<Face>& faces);

}  // namespace eqmesh

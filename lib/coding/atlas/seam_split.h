// TEXCOORD_0 of a decoded level from the atlas (atlas_layout.h): every level face
// inherits its corners' texture coordinates from its base face by the 1-to-4 rule
// (a new vertex takes the mean of its edge's ends), and a vertex whose faces give
// it different coordinates (a chart border: an unpaired base edge, a base vertex)
// is split into one copy per coordinate. Positions stay those of the welded mesh,
// so the surface stays watertight; only the index buffer sees the seams.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "coding/atlas/atlas_layout.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

struct SeamSplitMesh {
  std::vector<uint32_t> source_vertex;  // output vertex -> vertex of ExtractLevel(mesh, level)
  std::vector<Face> faces;              // ExtractLevel's faces, in its order, on output vertices
  std::vector<std::array<float, 2>> texcoords;  // per output vertex
};

// Vertices keep their index where they have one texture coordinate (the first
// face corner using them decides); split copies follow in order of first use.
// `corners` holds the atlas faces' corner coordinates: base faces then kept faces.
SeamSplitMesh SplitLevelAtSeams(const SemiRegularMesh& mesh, int level, const std::vector<FaceTexCoords>& corners);

// The corner coordinates of every face of `level` (its faces, then the kept
// faces), as SplitLevelAtSeams assigns them.
std::vector<FaceTexCoords> LevelCornerTexCoords(const SemiRegularMesh& mesh, int level,
                                                const std::vector<FaceTexCoords>& corners);

}  // namespace eqmesh

// Lays out the texture atlas of a remeshed primitive (the encoder's half of
// coding/atlas/atlas_layout.h): base faces paired across edges into square cells,
// cells sized by the surface area they carry so the texel density is even, and
// packed into the texture by shelves.
//
// Pairs share their diagonal, so a third of the base edges are no seam; the
// greedy pairing prefers each face's longest edge, which the right isosceles
// layout maps to the hypotenuse. Shelf packing (tallest first) follows the
// "next-fit decreasing height" strip packing of Coffman et al. (SIAM J. Comput.
// 1980); the largest density that fits is found by bisection.
#pragma once

#include <cstdint>

#include "coding/atlas/atlas_layout.h"
#include "mesh/semi_regular.h"

namespace eqmesh::texture {

struct AtlasBuildOptions {
  uint32_t width = 1024, height = 1024;  // texel grid (the largest output texture)
  uint32_t gutter = 4;                   // texels inside each cell's border
};

// Surface area each atlas face carries: a base face's finest faces of `mesh`
// (decoded positions), a kept face's own area.
std::vector<double> AtlasFaceAreas(const SemiRegularMesh& mesh);

// The layout for `mesh` (decoded at full resolution). Every face gets a cell of at
// least 2 * gutter + 2 texels; fails when even those do not fit the grid.
StatusOr<AtlasLayout> BuildAtlas(const SemiRegularMesh& mesh, const AtlasBuildOptions& options);

}  // namespace eqmesh::texture

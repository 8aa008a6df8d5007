// PerturbVertices: a deterministic noisy copy of a mesh, the yardstick of
// "mesh vs a 0.1 %-of-diagonal noisy copy" comparisons and the README demo.
#pragma once

#include <cstdint>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// Moves every vertex by exactly fraction x (bbox diagonal) in a direction
// drawn uniformly on the sphere (SampleRng, rejection from the cube, so the
// output is the same on every platform). Connectivity is unchanged.
// fraction must be finite and in [0, 1]; the mesh must have a face and finite
// coordinates.
StatusOr<Mesh> PerturbVertices(const Mesh& mesh, double fraction, uint64_t seed);

}  // namespace eqmesh

// Synthetic shapes that break a base domain sized by a vertex ratio: thin
// necks, thin tubes, long spikes and handles (pmp-library style: built in the
// test, no files). All are closed, manifold and outward oriented.
#pragma once

#include "mesh/mesh.h"

namespace eqmesh::testing {

// Two unit spheres at z = -2 and z = +2 joined by a neck of radius `neck`
// (a surface of revolution around z).
Mesh MakeDumbbell(double neck = 0.1);

// An icosphere whose surface is pulled out into six spikes of length `length`
// along the coordinate axes (genus 0).
Mesh MakeSpikyStar(double length = 2.0);

// A rounded plate with three holes (genus 3): the boundary of a voxel plate,
// smoothed by Laplacian steps so that no crease is sharp.
Mesh MakePretzel();

// Genus of a closed, connected, manifold mesh from its Euler characteristic.
int ClosedGenus(const Mesh& mesh);

}  // namespace eqmesh::testing

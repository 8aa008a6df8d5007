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

// The closed surface of the box [0, sx] x [0, sy] x [0, sz], each side a grid
// of about `cells_per_unit` squares per unit length (two triangles each): sharp
// 90-degree creases along its twelve edges, corners of three creases.
Mesh MakeGridBox(double sx, double sy, double sz, int cells_per_unit);

// Genus of a closed, connected, manifold mesh from its Euler characteristic.
int ClosedGenus(const Mesh& mesh);

}  // namespace eqmesh::testing

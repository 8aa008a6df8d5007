// Helpers shared by the tests: synthetic shapes (pmp-library style) and the
// location of the shared meshes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace eqmesh::testing {

// ../shared/<relative>, e.g. SharedPath("meshes/small/cow.ply").
std::string SharedPath(const std::string& relative);
// True when ../shared/meshes exists (CI has it; a bare checkout may not).
bool HaveSharedMeshes();

// Unit icosphere refined `subdivisions` times (20 * 4^s faces), CCW outward.
Mesh MakeIcosphere(int subdivisions, double radius = 1.0);
// Torus around z, major radius R, minor r, n x m quads split in two.
Mesh MakeTorus(int n, int m, double major_radius = 1.0, double minor_radius = 0.35);
// Flat disc in the z = 0 plane with `rings` rings: a mesh with one boundary loop.
Mesh MakeDisc(int rings, double radius = 1.0);
// A closed cylinder of radius r and height h around z, `around` vertices per
// ring and `rings` rings, capped by fans: two creases that are closed loops.
Mesh MakeCappedCylinder(double r, double h, int around, int rings);

// A unit cube, two triangles per side (outward), and its twelve edges (the
// sides' borders, not their diagonals): the shape crease tags are made for.
struct CubeWithEdges {
  Mesh mesh;
  std::vector<std::array<uint32_t, 2>> edges;
};
CubeWithEdges MakeCube();

// Every face of `mesh` with three corners of its own, as flat-shaded exports
// write them (each face its own component).
Mesh MakeTriangleSoup(const Mesh& mesh);
// `a` with `b` moved by `shift` appended as a second component.
Mesh WithComponent(Mesh a, const Mesh& b, const Vec3& shift);
// The largest side of the mesh's bounding box.
double LargestExtent(const Mesh& mesh);

}  // namespace eqmesh::testing

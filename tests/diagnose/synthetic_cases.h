// Small hand-built meshes with one known defect each, for the topology,
// diagnosis and repair tests (test_support.h has the clean shapes).
#pragma once

#include "mesh/mesh.h"

namespace eqmesh::testing {

// Two triangles sharing only vertex 0 (a "bowtie"): one pinched vertex.
Mesh MakeBowtie();
// Two tetrahedra sharing one vertex: closed, one pinched vertex, 2 components.
Mesh MakeTetrahedraSharingVertex();
// Closed tetrahedron, CCW outward.
Mesh MakeTetrahedron(const Vec3& offset = Vec3::Zero());
// Three triangles on edge (0, 1): one non-manifold edge.
Mesh MakeThreeFacesOnEdge();
// Icosphere(1) with face `face` reversed.
Mesh MakeSphereWithFlippedFace(int face);
// Mobius strip of `n` quads (2n triangles): non-orientable, one boundary loop.
Mesh MakeMobiusStrip(int n);
// Icosphere(2) whose lower faces use copies of their vertices: two open halves
// whose rims coincide exactly, i.e. a sphere to be welded shut.
Mesh MakeSplitSphere();
// Unit triangle in z = 0 (CCW seen from +z).
Mesh MakeTriangle();

// Concatenates b after a (indices of b shifted).
Mesh Concatenate(const Mesh& a, const Mesh& b);
// Signed volume of a closed mesh (positive when oriented outward).
double SignedVolume(const Mesh& mesh);

}  // namespace eqmesh::testing

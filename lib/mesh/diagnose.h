// Mesh diagnosis: the counts `eqmesh info` prints and the remesher checks before
// it starts (boundary, manifoldness, orientation, components, genus, degeneracy).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"

namespace eqmesh {

struct DiagnoseOptions {
  // A face with distinct indices is degenerate ("zero area") when twice its area
  // is at most this fraction of its longest edge squared, i.e. its height is
  // below tolerance * longest edge. Scale-free, so it means the same for a mesh
  // in millimetres and one in metres. 0 keeps only exactly-zero areas.
  double degenerate_area_tolerance = 1e-12;
};

struct ComponentDiagnosis {
  size_t faces = 0;
  size_t vertices = 0;  // vertex fans in the component (a pinched vertex counts once per fan)
  size_t edges = 0;
  size_t boundary_edges = 0;
  size_t boundary_loops = 0;
  size_t non_manifold_edges = 0;
  size_t non_manifold_vertices = 0;  // pinched vertices with a fan in this component
  bool closed = false;               // no boundary edges
  bool orientable = true;            // some choice of face flips makes it consistent
  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  int64_t euler_characteristic = 0;  // V - E + F
  // (2 - chi - b) / 2, with pinched vertices counted once per fan (the genus
  // after splitting them); -1 where undefined: non-manifold edges, or a
  // negative or odd numerator, or a non-orientable component.
  int64_t genus = -1;
};

struct MeshDiagnosis {
  size_t vertices = 0;             // as in the Mesh (readers may have dropped some)
  size_t referenced_vertices = 0;  // used by at least one face
  size_t faces = 0;
  size_t edges = 0;
  size_t invalid_faces = 0;     // an index >= vertices: ignored by everything else
  size_t boundary_edges = 0;    // exactly one face
  size_t boundary_loops = 0;
  size_t non_manifold_edges = 0;     // more than two faces
  size_t non_manifold_vertices = 0;  // star in > 1 fan ("pinched")
  size_t inconsistent_edges = 0;     // two faces traversing it the same way
  size_t components = 0;             // face-connected through edges
  size_t vertex_connected_components = 0;  // faces joined through shared vertices too
  size_t closed_components = 0;
  std::vector<int64_t> closed_genus;  // one per closed component, in component order
  std::vector<ComponentDiagnosis> component_details;  // indexed like FaceComponents()
  size_t degenerate_faces = 0;   // repeated index or (near) zero area
  size_t duplicate_positions = 0;  // vertices whose position equals an earlier vertex's
  size_t non_finite_positions = 0; // vertices with a NaN or infinite coordinate
  double bbox_diagonal = 0.0;

  // Edge- and vertex-manifold, every face valid. Orientation is separate.
  bool IsManifold() const {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 && invalid_faces == 0;
  }
  // What the remesher needs: manifold, consistently oriented, nothing degenerate.
  bool IsCleanForRemeshing() const {
    return IsManifold() && inconsistent_edges == 0 && degenerate_faces == 0 && non_finite_positions == 0;
  }
};

// Diagnoses `mesh`; never fails (bad indices are counted, not trusted). Linear
// time apart from small per-vertex sorts and one O(V log V) position sort.
MeshDiagnosis Diagnose(const Mesh& mesh, const DiagnoseOptions& options = {});
// Same, reusing an already built topology of `mesh`.
MeshDiagnosis Diagnose(const Mesh& mesh, const MeshTopology& topology, const DiagnoseOptions& options = {});

// True when face f of `mesh` (indices assumed in range) has a repeated index or
// (near) zero area in the sense of DiagnoseOptions::degenerate_area_tolerance.
bool IsDegenerateFace(const Mesh& mesh, const Face& face, double area_tolerance);

// Number of vertices whose position is bitwise-equal (after -0 == +0) to that of
// a lower-numbered vertex. Non-finite positions never count as duplicates.
size_t CountDuplicatePositions(const std::vector<Vec3>& positions);

// For every vertex the lowest-numbered vertex with exactly the same position
// (itself when unique). Non-finite positions map to themselves.
std::vector<uint32_t> FirstVertexWithSamePosition(const std::vector<Vec3>& positions);

}  // namespace eqmesh

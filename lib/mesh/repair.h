// Topological repair before remeshing (the remesher's --repair flag).
//
// RepairForRemeshing runs these steps, in this order, each deterministic
// (WeldSeams, below, runs step 1 alone):
//  1. weld   Vertices with bitwise-identical positions (-0 == +0) are merged
//            into the lowest-numbered one, but only where the merge (a) keeps
//            every edge at <= 2 faces and (b) actually joins surface, i.e. the
//            merged star has fewer fans than the two stars had together. A weld
//            that would only pinch two sheets at a point is refused.
//  2. drop   Faces with a repeated index or (near) zero area (see
//            DiagnoseOptions::degenerate_area_tolerance), then duplicate faces
//            (same three vertices in any order; the first one is kept).
//  3. edges  On every edge with > 2 faces keep the first face and the first
//            face running it the other way (else the second face), and detach
//            the others: their incidence on the edge is cut and their corners
//            are moved to new copies of the endpoints wherever the cut separates
//            them from the kept faces. A face still stuck on an over-full edge
//            (both endpoints reconnect around the edge) gets private copies of
//            the two endpoints.
//  4. fans   Every vertex whose star has k > 1 fans becomes k vertices (the fan
//            holding the lowest face keeps the original index).
//  5. orient Per component, faces are flipped to agree with the component's
//            lowest face; non-orientable components are cut along the conflict
//            edges (and step 4 rerun) until consistent. Components with boundary
//            then take whichever global orientation flips fewer input faces;
//            closed components are turned so their signed volume is positive
//            (outward normals).
//  6. compact Unreferenced vertices are dropped; the others keep their order.
//
// Afterwards the mesh has no degenerate face, no non-manifold edge or vertex and
// no inconsistently oriented edge; RepairForRemeshing checks this and returns
// kInternal if it ever does not hold. Boundaries are not filled and duplicate
// positions created by steps 3-5 are intended (they are seams, not errors).
#pragma once

#include <cstddef>
#include <string>

#include "core/status.h"
#include "mesh/diagnose.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct RepairOptions {
  double degenerate_area_tolerance = DiagnoseOptions{}.degenerate_area_tolerance;
};

struct RepairReport {
  size_t vertices_welded = 0;           // step 1: vertices merged into an earlier one
  size_t welds_refused = 0;             // step 1: identical positions left apart
  size_t degenerate_faces_removed = 0;  // step 2: repeated index or zero area
  size_t duplicate_faces_removed = 0;   // step 2
  size_t non_manifold_edges_split = 0;  // step 3: edges that had > 2 faces
  size_t faces_detached = 0;            // step 3: face-edge incidences cut
  size_t vertices_split = 0;            // steps 3-5: new vertex copies created
  size_t non_manifold_vertices_split = 0;  // step 4: pinched vertices found
  size_t orientation_cuts = 0;          // step 5: edges cut in non-orientable components
  size_t faces_flipped = 0;             // step 5: faces whose final orientation differs
  size_t components_turned_outward = 0; // step 5: closed components reversed wholesale
  size_t unreferenced_vertices_removed = 0;  // step 6

  // True when the repair changed nothing.
  bool Unchanged() const;
  // One line, e.g. "welded 3, removed 2 degenerate + 0 duplicate faces, ...".
  std::string Summary() const;
};

// Repairs `mesh` as described above. Fails (kInvalidMesh) on an out-of-range
// index or a non-finite coordinate of a referenced vertex, which no topological
// repair can fix. `report` may be null.
StatusOr<Mesh> RepairForRemeshing(const Mesh& mesh, RepairReport* report,
                                  const RepairOptions& options = {});

// Step 1 alone, for input that is not repaired otherwise: welds vertices at
// bitwise-identical positions wherever that joins surface and leaves no
// non-manifold edge, pinched vertex or inconsistently oriented edge the input
// did not have. Seams that exporters split (UV, normal or material seams, and
// triangle soups, whose every face has its own corners) close into the surface
// they belong to; the geometry is the same, so is any distance to it. Faces keep
// their order and vertices their numbers (merged ones become unreferenced).
// Input with an out-of-range index or a non-finite coordinate comes back as it
// is, for the caller's checks to name. `vertices_welded` may be null.
Mesh WeldSeams(const Mesh& mesh, size_t* vertices_welded = nullptr);

}  // namespace eqmesh

// What the remesher accepts, and the one-line error naming the first problem
// of anything else (non-manifold edge or vertex, inconsistent orientation,
// non-finite coordinate, bad index).
#pragma once

#include <string>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"

namespace eqmesh {

// OK when `mesh` is a manifold, consistently oriented triangle mesh with finite
// coordinates and in-range indices. Faces with a repeated index and zero-area
// faces are tolerated (the caller drops the former).
Status CheckRemeshable(const Mesh& mesh, const MeshTopology& topology);

}  // namespace eqmesh

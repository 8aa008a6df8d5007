// Property checks shared by the remesher tests: topology of each level, flips
// against the input, distances between surfaces.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh::testing {

struct LevelTopology {
  bool manifold = false;        // no edge with > 2 faces, no inconsistent edge, no pinched vertex
  size_t boundary_edges = 0;
  size_t boundary_loops = 0;
  int64_t euler = 0;            // V - E + F
};
LevelTopology CheckLevelTopology(const Mesh& mesh);

// Faces whose normal opposes the input's at the closest input point of their
// centroid, and faces with (near) zero area.
struct FlipCount {
  size_t flipped = 0;
  size_t degenerate = 0;
};
FlipCount CountFlips(const Mesh& remesh, const Mesh& input);

// Largest distance from a vertex of `points` to the surface `surface`.
double MaxVertexDistance(const Mesh& points, const Mesh& surface);
// Vertex-sampled symmetric RMS distance turned into PSNR (bbox diagonal of `a`).
double VertexPsnrDb(const Mesh& a, const Mesh& b);

}  // namespace eqmesh::testing

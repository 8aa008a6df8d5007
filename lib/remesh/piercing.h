// One refinement step j -> j+1 of the normal remesh: place every odd vertex and
// carry the parameterization of the input over to level j+1.
//
// Follows Guskov, Vidimče, Sweldens, Schröder, "Normal Meshes" (SIGGRAPH 2000),
// §4: from the butterfly prediction, along the predicted normal (both exactly as
// the codec's wavelet/butterfly.h computes them, so a normal vertex's unlifted
// detail is purely normal), intersect the input surface; accept the hit closest
// to the prediction whose parameter lies in the edge's diamond; otherwise use
// the parametric midpoint (a non-normal vertex).
// Departures (see the notes in ../shared/notes/remeshing.md §4.4-4.5):
//  * The diamond test is stricter: the parameter must lie in the kite spanned by
//    the edge and the two face centroids, shrunk by 10 % toward the edge midpoint,
//    and the four children of each face must stay positively oriented with a
//    minimum quality in the chart; otherwise the edge is demoted to its midpoint.
//  * Hits are searched only within |t| <= kReach * edge length.
//  * The parameterization is updated by the affine 1-to-4 split of each face at
//    its three new points; instead of Guskov's Floater smoothing between levels,
//    RefineOptions can then re-project each input vertex onto the closest new
//    triangle (locally, and globally with a normal test), so the parameter
//    follows the 3D remesh and the distortion of the base map stops compounding.
//  * Boundary edges are never pierced: the new vertex is the parametric midpoint
//    on the input's boundary polyline (VertexKind::kBoundary).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"
#include "mesh/triangle_bvh.h"
#include "remesh/param_point.h"

namespace eqmesh {

struct InputSurface {
  const Mesh* mesh = nullptr;
  const TriangleBvh* bvh = nullptr;
  std::vector<uint8_t> is_boundary;     // per input vertex
  std::vector<uint32_t> face_offsets;   // vertex -> incident faces (CSR)
  std::vector<uint32_t> vertex_faces;
  std::vector<Vec3> normals;            // area-weighted vertex normals (not unit)

  InputSurface(const Mesh& m, const TriangleBvh& b, std::vector<uint8_t> boundary);
};

// How the parameterization follows each level (see the departures above).
struct RefineOptions {
  // Project each input vertex onto the closest child triangle of its face and
  // the face's neighbours.
  bool project_locally = false;
  // > 0: then move it to the closest same-facing triangle of the whole level
  // when that is closer than this ratio times its current distance.
  double global_projection_ratio = 0.0;
};

struct LevelStats {
  size_t normal = 0;
  size_t non_normal = 0;
  size_t boundary = 0;
  double rms_error = 0.0;  // input vertices to the level-(j+1) remesh
};

// `hierarchy` must have at least j+1 levels. `positions` holds level-j positions
// on entry and level-(j+1) positions on return; `kinds` gets the odd vertices'
// kinds appended; `params` (one per input vertex) moves from level j to j+1.
void RefineLevel(const SemiRegularHierarchy& hierarchy, int j, const InputSurface& surface,
                 const RefineOptions& options, std::vector<Vec3>* positions, std::vector<VertexKind>* kinds,
                 std::vector<ParamPoint>* params, LevelStats* stats);

}  // namespace eqmesh

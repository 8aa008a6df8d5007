// Influence of each base vertex on the reconstructed surface, the weight of its
// squared error in the base-mesh R-D choice (base_mesh_encoder.h).
//
// w_i = sum over finest-level vertices v of phi_i(v)^2, where phi_i is the
// interpolating butterfly subdivision (lib/wavelet/butterfly.h stencils, all
// details zero) of the unit impulse at base vertex i, refined `levels` times.
// A base error e_i with no correcting details moves vertex v by phi_i(v) e_i, so
// w_i |e_i|^2 is its contribution to the per-vertex squared error the level coders
// minimise. Used unchanged for the lifted scaling values (an approximation: the
// lifted synthesis basis is slightly wider).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

std::vector<double> BaseInfluenceWeights(const SemiRegularHierarchy& hierarchy);

// For a base that IS the decoded surface (no refinement levels): per vertex, the
// mean over its faces of n n^T (unit face normals), so that e^T Q e is the mean
// squared distance a displacement e puts the vertex from the planes of its faces.
// A slide within a flat region costs nothing; across a crease it does (Garland and
// Heckbert's error quadric, SIGGRAPH 1997, averaged instead of summed). Vertices
// with no non-degenerate face get the identity (|e|^2).
std::vector<Eigen::Matrix3d> SurfaceErrorQuadrics(const Mesh& base);

}  // namespace eqmesh

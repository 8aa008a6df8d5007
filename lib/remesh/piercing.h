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
//    its three new points, without Guskov's Floater smoothing between levels
//    (Tutte smoothing of the input vertices inside their faces moves the
//    parameter away from the remesh vertices already placed, and the kite test
//    then refuses a quarter of the hits). The base domain's cost keeps its
//    triangles well shaped instead (base_domain.h).
//  * Charts are trusted only where they are consistent: an input triangle whose
//    chart image flips is skipped, and a forward map takes the nearest face in
//    breadth-first order that contains its target.
//  * On levels with at least as many faces as the input, hits are validated in
//    the 3D diamond of the two level-j triangles and demoted midpoints are
//    pierced from the 3D edge midpoint: there an input triangle spans many
//    level-j faces and its chart image would be unfolded across all of them
//    (bench meshes: 4-9x fewer folds, normal share 0.99 instead of 0.95, no
//    degenerate faces from failed forward maps).
//    There a hit is taken only on an input face within two vertex rings of
//    the faces under the edge's ends (where those are known): the diamond test
//    cannot tell the edge's own sheet from another that passes within reach (a
//    curled thin part facing the same way, or a part modelled through the
//    surface), and a hit there puts the vertex on the wrong sheet, a fold every
//    later level inherits (mannequin-devil: 35 folds -> 1; dino keeps its five
//    levels without folds instead of dropping to three;
//    bench/log/2026-12-07-folds-where-the-input-crosses-itself.md).
//  * Each level's folded faces and lopsided vertices are repaired before the
//    next level is pierced from them (placement_repair.cpp), where Guskov et
//    al. keep the hit closest to the prediction.
//  * Boundary edges are never pierced: the new vertex is the parametric midpoint
//    on the input's boundary polyline (VertexKind::kBoundary).
//  * Tagged edges (base edges along an input crease chain, and their halves)
//    are not pierced either while their ends lie on the chain: the new vertex is
//    the chain's arc-length midpoint between them (crease_curves.h), and the
//    butterfly predicts it along the crease (wavelet/butterfly.cpp, rule C1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"
#include "mesh/triangle_bvh.h"
#include "remesh/crease_curves.h"
#include "remesh/param_point.h"
#include "remesh/quality_checks.h"
#include "wavelet/butterfly.h"

namespace eqmesh {

struct InputSurface {
  const Mesh* mesh = nullptr;
  const TriangleBvh* bvh = nullptr;
  std::vector<uint8_t> is_boundary;     // per input vertex
  std::vector<uint32_t> face_offsets;   // vertex -> incident faces (CSR)
  std::vector<uint32_t> vertex_faces;
  std::vector<Vec3> face_normals;       // FaceCrossProducts (not unit)
  std::vector<Vec3> normals;            // area-weighted vertex normals (not unit)
  std::vector<uint32_t> face_part;      // FacePartsForFoldTest (empty: one part)
  CreaseCurves creases;                 // followed by remesh edges along them
  // Input edges with one face (its boundary curves), by LowerX, and the longest
  // of them. Built once here, not per untangling (it runs after every level).
  std::vector<Edge> boundary_edges;
  double longest_boundary_edge = 0.0;

  InputSurface(const Mesh& m, const TriangleBvh& b, std::vector<uint8_t> boundary);

  // The point of the input's boundary curves closest to `target` within
  // `reach`, if any (the untangler's boundary slides); only the slab of
  // boundary_edges within reach in x is scanned.
  std::optional<Vec3> ClosestBoundaryPoint(const Vec3& target, double reach) const;

 private:
  // Smaller x of an edge's ends: the key boundary_edges is sorted by.
  double LowerX(const Edge& e) const;
};

// The input part (InputSurface::face_part) each base face of a remesh covers,
// so a face of any level is judged against its own part and pierced onto it
// only: the faces of base face t at level L are [t * 4^L, (t + 1) * 4^L), and
// no face spans two parts. Empty for an input of one part.
struct RemeshParts {
  std::vector<uint32_t> of_base_face;

  uint32_t Of(uint32_t face, int level) const {
    return of_base_face.empty() ? kAnyPart : of_base_face[face >> (2 * level)];
  }
};

// The parts of a base domain's faces, whose corners are the input vertices
// `base_to_input` names.
RemeshParts BaseFaceParts(const InputSurface& surface, const std::vector<uint32_t>& base_to_input,
                          const std::vector<Face>& base_faces);

// Levels with at least this many faces per input face are refined in 3D: hits
// are validated and demoted midpoints placed in the 3D diamond rather than
// through charts of the input's parameters. Measured on the bench meshes: 0.5
// (the level after the last one coarser than the input's half) folds 3x fewer
// faces than 1; 0.15 loses up to 20 dB where coarse levels still need the
// charts' protection on thin parts.
inline constexpr double kFineLevelFaceRatio = 0.5;

// Whether a level of `level_faces` faces over an input of `input_faces` is
// refined in 3D (kFineLevelFaceRatio).
inline bool RefinedIn3d(size_t level_faces, size_t input_faces) {
  return static_cast<double>(level_faces) >= kFineLevelFaceRatio * static_cast<double>(input_faces);
}

struct LevelStats {
  double rms_error = 0.0;  // input vertices to the level-(j+1) remesh
  std::vector<uint32_t> folded_faces;  // level-(j+1) faces folded against the input
};

// `hierarchy` must have at least j+1 levels. `positions` holds level-j positions
// on entry and level-(j+1) positions on return; `kinds` gets the odd vertices'
// kinds appended; `on_faces` runs alongside `positions`: the input triangle each
// vertex lies on (kNoFace where not known), which lets the fold scan skip the
// input search for faces that plainly agree with the surface under their corners.
// `params` (one per input vertex) moves from level j to j+1.
// `stencils`: BuildButterflyStencils(hierarchy, j), built by the caller so the
// untangling can reuse it (StencilCache). `creases` (optional) runs alongside
// `positions` too: where each vertex lies on the input's crease chains; edges
// along a chain are refined onto it (crease_curves.h) and the odd vertices'
// places are appended.
void RefineLevel(const SemiRegularHierarchy& hierarchy, int j, const InputSurface& surface, const RemeshParts& parts,
                 const StencilTable& stencils, std::vector<Vec3>* positions, std::vector<uint32_t>* on_faces,
                 std::vector<VertexKind>* kinds, std::vector<ParamPoint>* params, LevelStats* stats,
                 std::vector<CreasePlace>* creases = nullptr);

}  // namespace eqmesh

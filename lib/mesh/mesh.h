// The triangle mesh every stage passes around: positions plus index triples.
// Free functions operate on it (pmp-library style); no half-edge structure is
// imposed on callers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/status.h"

namespace eqmesh {

using Vec3 = Eigen::Vector3d;
using Face = std::array<uint32_t, 3>;

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Face> faces;  // counter-clockwise seen from outside

  size_t num_vertices() const { return positions.size(); }
  size_t num_faces() const { return faces.size(); }
};

struct BoundingBox {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(0.0);
  double Diagonal() const { return (max - min).norm(); }
};

// Every face index below the vertex count and every vertex a face uses finite;
// else kInvalidMesh naming the first face or vertex that is not.
Status CheckIndicesAndCoordinates(const Mesh& mesh);

// Removes the vertices no face uses, keeping the others in order (faces
// renumbered); returns how many were removed.
size_t DropUnreferencedVertices(Mesh* mesh);

// Box of the vertices that some face uses (unreferenced vertices do not count);
// all zeros for an empty mesh.
BoundingBox ComputeBoundingBox(const Mesh& mesh);

// Diagonal of ComputeBoundingBox: the PSNR peak of the seed paper.
double BoundingBoxDiagonal(const Mesh& mesh);

// Power of two that brings the referenced vertices' largest bounding-box side
// near 1, limited so that no coordinate leaves [-2^400, 2^400]; 1 for an empty
// or non-finite box. Scaling by it is exact, so stages that square lengths
// (areas, squared distances: they overflow near 1e155 and underflow near
// 1e-155) work on any finite input at its own precision.
double PowerOfTwoUnitScale(const Mesh& mesh);

// Number of distinct vertices referenced by faces: the "input vertices" that
// bits-per-vertex is measured against.
size_t CountReferencedVertices(const Mesh& mesh);

// Area-weighted vertex normals (zero vector for isolated or degenerate fans).
std::vector<Vec3> VertexNormals(const Mesh& mesh);
// ext_spec's "Reconstruction of normals": VertexNormals, with (0, 0, 1) where a
// vertex has no area around it.
std::vector<Vec3> UnitVertexNormals(const Mesh& mesh);
// The same over `faces` for vertices [0, num_vertices) of `positions`: ext_spec's
// normative rule (the wavelet frames' F1), whose order of operations (face cross
// products summed in face order, then n / |n|) a decoder must keep.
std::vector<Vec3> VertexNormals(const std::vector<Face>& faces, size_t num_vertices,
                                const std::vector<Vec3>& positions);

// (b - a) x (c - a) of every face (a, b, c): its normal times twice its area.
std::vector<Vec3> FaceCrossProducts(const Mesh& mesh);

// Angle at `apex` between its edges to a and b, in radians (pi/2 when an edge
// has zero length).
double CornerAngle(const Vec3& apex, const Vec3& a, const Vec3& b);

// The corner angles at v of the faces using it, summed: 2 pi where an interior
// vertex is flat, less at a tip. Scans every face.
double AngleSumAt(const Mesh& mesh, uint32_t v);

}  // namespace eqmesh

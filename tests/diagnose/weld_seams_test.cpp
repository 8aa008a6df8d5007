// WeldSeams: the repair's weld on its own, which must leave a clean mesh clean.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "diagnose/synthetic_cases.h"
#include "mesh/diagnose.h"
#include "mesh/repair.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// The faces' corner positions, face by face: the geometry a weld must keep.
std::vector<Vec3> CornerPositions(const Mesh& mesh) {
  std::vector<Vec3> corners;
  for (const Face& f : mesh.faces)
    for (uint32_t v : f) corners.push_back(mesh.positions[v]);
  return corners;
}

bool SameMesh(const Mesh& a, const Mesh& b) { return a.positions == b.positions && a.faces == b.faces; }

TEST(WeldSeams, TriangleSoupClosesIntoTheSurface) {
  const Mesh torus = testing::MakeTorus(12, 8);
  const Mesh soup = testing::MakeTriangleSoup(torus);
  ASSERT_EQ(Diagnose(soup).components, torus.num_faces());
  size_t welded = 0;
  const Mesh w = WeldSeams(soup, &welded);
  EXPECT_EQ(welded, soup.num_vertices() - torus.num_vertices());
  const MeshDiagnosis d = Diagnose(w);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_EQ(d.referenced_vertices, torus.num_vertices());
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{1}));
  EXPECT_EQ(d.inconsistent_edges, 0u);
  EXPECT_EQ(CornerPositions(w), CornerPositions(soup));
}

TEST(WeldSeams, SplitSphereIsWeldedShut) {
  size_t welded = 0;
  const Mesh w = WeldSeams(testing::MakeSplitSphere(), &welded);
  EXPECT_GT(welded, 0u);
  const MeshDiagnosis d = Diagnose(w);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_TRUE(d.IsManifold());
}

TEST(WeldSeams, CleanMeshIsLeftAlone) {
  const Mesh sphere = testing::MakeIcosphere(2);
  size_t welded = 1;
  EXPECT_TRUE(SameMesh(WeldSeams(sphere, &welded), sphere));
  EXPECT_EQ(welded, 0u);
}

TEST(WeldSeams, WeldThatOnlyPinchesIsRefused) {
  // Two tetrahedra touching at one point, (1, 0, 0), through two vertices:
  // welding them would pinch two closed sheets together.
  const Mesh m = testing::WithComponent(testing::MakeTetrahedron(), testing::MakeTetrahedron(), Vec3(1, 0, 0));
  ASSERT_EQ(m.positions[4], m.positions[1]);
  size_t welded = 1;
  EXPECT_TRUE(SameMesh(WeldSeams(m, &welded), m));
  EXPECT_EQ(welded, 0u);
}

TEST(WeldSeams, OppositelyOrientedSheetsStayApart) {
  // Two triangles sharing an edge's positions and running it the same way:
  // welded, the edge would be inconsistently oriented (the repair welds them
  // and then turns one over; a weld alone must not).
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0)};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  size_t welded = 1;
  EXPECT_TRUE(SameMesh(WeldSeams(m, &welded), m));
  EXPECT_EQ(welded, 0u);
  // Turned the other way round, the second joins the first.
  m.faces[1] = {4, 3, 5};
  const Mesh w = WeldSeams(m, &welded);
  EXPECT_EQ(welded, 2u);
  EXPECT_EQ(Diagnose(w).components, 1u);
  EXPECT_EQ(Diagnose(w).inconsistent_edges, 0u);
}

TEST(WeldSeams, InvalidInputComesBackUnchanged) {
  Mesh m = testing::MakeTriangleSoup(testing::MakeIcosphere(1));
  m.positions[7].x() = std::numeric_limits<double>::quiet_NaN();
  size_t welded = 1;
  const Mesh w = WeldSeams(m, &welded);
  EXPECT_EQ(welded, 0u);
  EXPECT_EQ(w.faces, m.faces);
  m.faces[0][0] = 100000;  // out of range
  EXPECT_EQ(WeldSeams(m, &welded).faces, m.faces);
}

}  // namespace
}  // namespace eqmesh

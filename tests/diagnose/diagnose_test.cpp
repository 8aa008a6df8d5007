#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "diagnose/synthetic_cases.h"
#include "mesh/diagnose.h"
#include "test_support.h"

namespace eqmesh {
namespace {

void ExpectClosedManifold(const MeshDiagnosis& d, int64_t genus) {
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_EQ(d.boundary_loops, 0u);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_EQ(d.non_manifold_vertices, 0u);
  EXPECT_EQ(d.inconsistent_edges, 0u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.closed_components, 1u);
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{genus}));
  EXPECT_EQ(d.degenerate_faces, 0u);
  EXPECT_TRUE(d.IsManifold());
  EXPECT_TRUE(d.IsCleanForRemeshing());
}

TEST(Diagnose, IcosphereIsClosedGenusZero) {
  const Mesh m = testing::MakeIcosphere(3);
  const MeshDiagnosis d = Diagnose(m);
  ExpectClosedManifold(d, 0);
  EXPECT_EQ(d.vertices, m.num_vertices());
  EXPECT_EQ(d.referenced_vertices, m.num_vertices());
  EXPECT_EQ(d.faces, m.num_faces());
  EXPECT_EQ(d.edges, 30u * 64u);
  EXPECT_EQ(d.duplicate_positions, 0u);
  EXPECT_NEAR(d.bbox_diagonal, 2.0 * std::sqrt(3.0), 0.2);
}

TEST(Diagnose, TorusIsClosedGenusOne) { ExpectClosedManifold(Diagnose(testing::MakeTorus(16, 8)), 1); }

TEST(Diagnose, DiscHasOneBoundaryLoopAndGenusZero) {
  const MeshDiagnosis d = Diagnose(testing::MakeDisc(5));
  EXPECT_EQ(d.boundary_edges, 30u);
  EXPECT_EQ(d.boundary_loops, 1u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.closed_components, 0u);
  ASSERT_EQ(d.component_details.size(), 1u);
  EXPECT_EQ(d.component_details[0].euler_characteristic, 1);
  EXPECT_EQ(d.component_details[0].genus, 0);
  EXPECT_TRUE(d.IsManifold());
}

TEST(Diagnose, PinchedVertexIsOneNonManifoldVertex) {
  const MeshDiagnosis d = Diagnose(testing::MakeTetrahedraSharingVertex());
  EXPECT_EQ(d.non_manifold_vertices, 1u);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_EQ(d.components, 2u);
  EXPECT_EQ(d.vertex_connected_components, 1u);
  EXPECT_EQ(d.closed_components, 2u);
  // Pinched vertices count once per fan, so both tetrahedra read genus 0.
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{0, 0}));
  EXPECT_FALSE(d.IsManifold());

  const MeshDiagnosis bowtie = Diagnose(testing::MakeBowtie());
  EXPECT_EQ(bowtie.non_manifold_vertices, 1u);
  EXPECT_EQ(bowtie.boundary_loops, 2u);
  EXPECT_EQ(bowtie.boundary_edges, 6u);
}

TEST(Diagnose, ThreeFacesOnAnEdgeIsOneNonManifoldEdgeOnly) {
  const MeshDiagnosis d = Diagnose(testing::MakeThreeFacesOnEdge());
  EXPECT_EQ(d.non_manifold_edges, 1u);
  EXPECT_EQ(d.non_manifold_vertices, 0u);  // explained by the edge
  EXPECT_EQ(d.inconsistent_edges, 0u);     // reported as non-manifold instead
  EXPECT_EQ(d.boundary_edges, 6u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.component_details[0].genus, -1);
  EXPECT_FALSE(d.IsManifold());
}

TEST(Diagnose, FlippedFaceGivesThreeInconsistentEdges) {
  const MeshDiagnosis d = Diagnose(testing::MakeSphereWithFlippedFace(5));
  EXPECT_EQ(d.inconsistent_edges, 3u);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_TRUE(d.IsManifold());
  EXPECT_FALSE(d.IsCleanForRemeshing());
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{0}));  // still orientable
}

TEST(Diagnose, MobiusStripHasUndefinedGenus) {
  const MeshDiagnosis d = Diagnose(testing::MakeMobiusStrip(10));
  EXPECT_EQ(d.boundary_loops, 1u);
  ASSERT_EQ(d.component_details.size(), 1u);
  EXPECT_FALSE(d.component_details[0].orientable);
  EXPECT_EQ(d.component_details[0].genus, -1);
  EXPECT_GT(d.inconsistent_edges, 0u);
}

TEST(Diagnose, DegenerateFacesAreCounted) {
  Mesh m = testing::MakeIcosphere(1);
  m.faces.push_back({0, 0, 1});                       // repeated index
  m.positions.push_back(0.5 * (m.positions[0] + m.positions[1]));
  const uint32_t mid = static_cast<uint32_t>(m.positions.size() - 1);
  m.faces.push_back({0, 1, mid});                     // collinear: zero area
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.degenerate_faces, 2u);
  EXPECT_FALSE(d.IsCleanForRemeshing());
  // A thin but honest sliver is not degenerate.
  Mesh sliver = testing::MakeTriangle();
  sliver.positions[2] = Vec3(0.5, 1e-6, 0);
  EXPECT_EQ(Diagnose(sliver).degenerate_faces, 0u);
  sliver.positions[2] = Vec3(0.5, 1e-14, 0);
  EXPECT_EQ(Diagnose(sliver).degenerate_faces, 1u);
}

TEST(Diagnose, DuplicatePositionsCountLaterCopies) {
  Mesh m = testing::MakeIcosphere(1);
  m.positions.push_back(m.positions[3]);
  m.positions.push_back(m.positions[3]);
  m.positions.push_back(Vec3(-0.0, 0.0, 0.0));
  m.positions.push_back(Vec3(0.0, -0.0, 0.0));  // -0 == +0
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.duplicate_positions, 3u);
  EXPECT_EQ(d.vertices, m.num_vertices());
  EXPECT_EQ(d.referenced_vertices, m.num_vertices() - 4);
}

TEST(Diagnose, SplitSphereHasTwoHalvesWithOneLoopEach) {
  const MeshDiagnosis d = Diagnose(testing::MakeSplitSphere());
  EXPECT_EQ(d.components, 2u);
  EXPECT_EQ(d.boundary_loops, 2u);
  for (const ComponentDiagnosis& c : d.component_details) EXPECT_EQ(c.genus, 0);
  EXPECT_GT(d.duplicate_positions, 0u);
}

TEST(Diagnose, BadInputIsCountedNotTrusted) {
  Mesh m = testing::MakeTriangle();
  m.faces.push_back({0, 1, 99});
  m.positions.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  m.positions.push_back(Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.invalid_faces, 1u);
  EXPECT_EQ(d.non_finite_positions, 2u);
  EXPECT_EQ(d.duplicate_positions, 0u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_FALSE(d.IsManifold());

  const MeshDiagnosis empty = Diagnose(Mesh{});
  EXPECT_EQ(empty.faces, 0u);
  EXPECT_EQ(empty.components, 0u);
  EXPECT_EQ(empty.bbox_diagonal, 0.0);
}

}  // namespace
}  // namespace eqmesh

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "diagnose/synthetic_cases.h"
#include "mesh/diagnose.h"
#include "mesh/repair.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// Repairs and checks the contract every repaired mesh must meet.
Mesh RepairAndCheck(const Mesh& input, RepairReport* report) {
  auto repaired = RepairForRemeshing(input, report);
  EXPECT_TRUE(repaired.ok()) << repaired.status().ToString();
  if (!repaired.ok()) return Mesh{};
  const MeshDiagnosis d = Diagnose(*repaired);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_EQ(d.non_manifold_vertices, 0u);
  EXPECT_EQ(d.inconsistent_edges, 0u);
  EXPECT_EQ(d.degenerate_faces, 0u);
  EXPECT_EQ(d.referenced_vertices, d.vertices);
  EXPECT_TRUE(d.IsCleanForRemeshing());
  // Idempotent: a repaired mesh needs nothing more.
  RepairReport again;
  auto twice = RepairForRemeshing(*repaired, &again);
  EXPECT_TRUE(twice.ok());
  EXPECT_TRUE(again.Unchanged()) << again.Summary();
  return std::move(repaired).value();
}

bool SameMesh(const Mesh& a, const Mesh& b) { return a.positions == b.positions && a.faces == b.faces; }

TEST(Repair, CleanMeshIsLeftAlone) {
  const Mesh m = testing::MakeTorus(12, 8);
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_TRUE(report.Unchanged()) << report.Summary();
  EXPECT_TRUE(SameMesh(m, r));
}

TEST(Repair, BowtieSplitsIntoTwoTriangles) {
  RepairReport report;
  const Mesh r = RepairAndCheck(testing::MakeBowtie(), &report);
  EXPECT_EQ(report.non_manifold_vertices_split, 1u);
  EXPECT_EQ(report.vertices_split, 1u);
  EXPECT_EQ(r.num_vertices(), 6u);
  EXPECT_EQ(r.num_faces(), 2u);
  EXPECT_EQ(Diagnose(r).components, 2u);
}

TEST(Repair, PinchedTetrahedraBecomeTwoClosedSolids) {
  RepairReport report;
  const Mesh r = RepairAndCheck(testing::MakeTetrahedraSharingVertex(), &report);
  EXPECT_EQ(report.non_manifold_vertices_split, 1u);
  const MeshDiagnosis d = Diagnose(r);
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{0, 0}));
  EXPECT_EQ(report.vertices_welded, 0u);  // the copies share a position but welding would pinch
}

TEST(Repair, ThreeFacesOnEdgeKeepsAConsistentPair) {
  RepairReport report;
  const Mesh input = testing::MakeThreeFacesOnEdge();
  const Mesh r = RepairAndCheck(input, &report);
  EXPECT_EQ(report.non_manifold_edges_split, 1u);
  EXPECT_EQ(report.faces_detached, 1u);
  EXPECT_EQ(r.num_faces(), 3u);
  // Faces 0 and 1 run the edge in opposite directions and stay joined; face 2 leaves.
  EXPECT_EQ(r.faces[0], input.faces[0]);
  EXPECT_EQ(r.faces[1], input.faces[1]);
  const MeshDiagnosis d = Diagnose(r);
  EXPECT_EQ(d.components, 2u);
  EXPECT_EQ(d.boundary_edges, 7u);
}

TEST(Repair, FlippedFaceIsFlippedBack) {
  RepairReport report;
  const Mesh r = RepairAndCheck(testing::MakeSphereWithFlippedFace(7), &report);
  EXPECT_EQ(report.faces_flipped, 1u);
  EXPECT_TRUE(SameMesh(r, testing::MakeIcosphere(1)));
}

TEST(Repair, InsideOutSphereIsTurnedOutward) {
  Mesh m = testing::MakeIcosphere(2);
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_EQ(report.components_turned_outward, 1u);
  EXPECT_EQ(report.faces_flipped, m.num_faces());
  EXPECT_GT(testing::SignedVolume(r), 0.0);
}

TEST(Repair, BoundaryComponentKeepsMajorityOrientation) {
  Mesh m = testing::MakeDisc(3);
  std::swap(m.faces[0][1], m.faces[0][2]);  // face 0 seeds the propagation
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_EQ(report.faces_flipped, 1u);
  EXPECT_TRUE(SameMesh(r, testing::MakeDisc(3)));
}

TEST(Repair, SplitSphereIsWeldedShut) {
  RepairReport report;
  const Mesh r = RepairAndCheck(testing::MakeSplitSphere(), &report);
  const Mesh ico = testing::MakeIcosphere(2);
  EXPECT_GT(report.vertices_welded, 0u);
  EXPECT_EQ(report.welds_refused, 0u);
  const MeshDiagnosis d = Diagnose(r);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{0}));
  EXPECT_EQ(r.num_vertices(), ico.num_vertices());
  EXPECT_EQ(r.num_faces(), ico.num_faces());
}

TEST(Repair, WeldThatWouldPinchOrOverfillAnEdgeIsRefused) {
  // A third triangle on edge (0, 1) but through copies of vertices 0 and 1:
  // welding the copies would create a non-manifold edge.
  Mesh m = testing::MakeThreeFacesOnEdge();
  m.positions.push_back(m.positions[0]);
  m.positions.push_back(m.positions[1]);
  m.faces[2] = {5, 6, 4};
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_EQ(report.vertices_welded, 0u);
  EXPECT_EQ(report.welds_refused, 2u);
  EXPECT_EQ(r.num_faces(), 3u);
}

TEST(Repair, DegenerateAndDuplicateFacesAreDropped) {
  Mesh m = testing::MakeIcosphere(1);
  const size_t n = m.num_faces();
  m.faces.push_back({1, 1, 2});
  m.faces.push_back({m.faces[3][1], m.faces[3][2], m.faces[3][0]});  // duplicate of face 3
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_EQ(report.degenerate_faces_removed, 1u);
  EXPECT_EQ(report.duplicate_faces_removed, 1u);
  EXPECT_EQ(r.num_faces(), n);
}

TEST(Repair, ZeroAreaSliverIsRemoved) {
  Mesh m = testing::MakeTriangle();
  m.positions.push_back(Vec3(0.5, 0, 0));
  m.faces.push_back({0, 3, 1});  // collinear
  RepairReport report;
  const Mesh r = RepairAndCheck(m, &report);
  EXPECT_EQ(report.degenerate_faces_removed, 1u);
  EXPECT_EQ(report.unreferenced_vertices_removed, 1u);
  EXPECT_EQ(r.num_faces(), 1u);
}

TEST(Repair, MobiusStripIsCutUntilOrientable) {
  RepairReport report;
  const Mesh r = RepairAndCheck(testing::MakeMobiusStrip(12), &report);
  EXPECT_GT(report.orientation_cuts, 0u);
  EXPECT_EQ(r.num_faces(), 24u);
}

TEST(Repair, IsDeterministic) {
  Mesh m = testing::Concatenate(testing::MakeSplitSphere(), testing::MakeMobiusStrip(9));
  m = testing::Concatenate(m, testing::MakeThreeFacesOnEdge());
  m = testing::Concatenate(m, testing::MakeTetrahedraSharingVertex());
  RepairReport a, b;
  const Mesh ra = RepairAndCheck(m, &a);
  const Mesh rb = RepairAndCheck(m, &b);
  EXPECT_TRUE(SameMesh(ra, rb));
  EXPECT_EQ(a.Summary(), b.Summary());
}

TEST(Repair, RejectsWhatItCannotFix) {
  Mesh bad_index = testing::MakeTriangle();
  bad_index.faces.push_back({0, 1, 9});
  EXPECT_EQ(RepairForRemeshing(bad_index, nullptr).status().code(), StatusCode::kInvalidMesh);
  Mesh nan = testing::MakeTriangle();
  nan.positions[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(RepairForRemeshing(nan, nullptr).status().code(), StatusCode::kInvalidMesh);
  Mesh all_degenerate = testing::MakeTriangle();
  all_degenerate.faces = {{0, 0, 1}};
  EXPECT_EQ(RepairForRemeshing(all_degenerate, nullptr).status().code(), StatusCode::kInvalidMesh);
}

}  // namespace
}  // namespace eqmesh

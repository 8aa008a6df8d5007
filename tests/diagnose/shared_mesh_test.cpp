// Diagnosis and repair on the shared test meshes (skipped without them).
// Expected values are those of shared/meshes/MANIFEST.md.
#include <gtest/gtest.h>

#include <string>

#include "mesh/diagnose.h"
#include "mesh_io/mesh_io.h"
#include "mesh/repair.h"
#include "test_support.h"

namespace eqmesh {
namespace {

Mesh ReadShared(const std::string& relative, ReadReport* report = nullptr) {
  auto mesh = ReadMesh(testing::SharedPath(relative), report);
  EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  return mesh.ok() ? std::move(mesh).value() : Mesh{};
}

void ExpectRepairedClean(const Mesh& mesh, RepairReport* report) {
  auto repaired = RepairForRemeshing(mesh, report);
  ASSERT_TRUE(repaired.ok()) << repaired.status().ToString();
  const MeshDiagnosis d = Diagnose(*repaired);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_EQ(d.non_manifold_vertices, 0u);
  EXPECT_EQ(d.inconsistent_edges, 0u);
  EXPECT_EQ(d.degenerate_faces, 0u);
  EXPECT_TRUE(d.IsCleanForRemeshing());
}

struct ClosedCase {
  const char* path;
  int64_t genus;
};

class ClosedSharedMesh : public ::testing::TestWithParam<ClosedCase> {};

TEST_P(ClosedSharedMesh, IsClosedManifoldWithManifestGenus) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  const Mesh m = ReadShared(GetParam().path);
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.boundary_edges, 0u);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_EQ(d.non_manifold_vertices, 0u);
  EXPECT_EQ(d.inconsistent_edges, 0u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.closed_genus, (std::vector<int64_t>{GetParam().genus}));
  // Repair leaves a clean closed mesh alone apart from orientation direction.
  RepairReport report;
  auto repaired = RepairForRemeshing(m, &report);
  ASSERT_TRUE(repaired.ok());
  EXPECT_EQ(report.vertices_split, 0u);
  EXPECT_EQ(report.non_manifold_edges_split, 0u);
}

INSTANTIATE_TEST_SUITE_P(Small, ClosedSharedMesh,
                         ::testing::Values(ClosedCase{"meshes/small/bunny_npm.obj", 0},
                                           ClosedCase{"meshes/small/fandisk.obj", 0},
                                           ClosedCase{"meshes/small/skull_low_resolution.obj", 2},
                                           ClosedCase{"meshes/small/rocker-arm.off", 1},
                                           ClosedCase{"meshes/small/max-planck_10k.obj", 0},
                                           ClosedCase{"meshes/bench/skull_50k.obj", 2}));

TEST(SharedMeshes, CowHasExactlyOnePinchedVertexAndRepairs) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  const Mesh m = ReadShared("meshes/small/cow.ply");
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.non_manifold_vertices, 1u);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  EXPECT_FALSE(d.IsManifold());
  RepairReport report;
  ExpectRepairedClean(m, &report);
  EXPECT_EQ(report.non_manifold_vertices_split, 1u);
}

TEST(SharedMeshes, StanfordBunnyHasFiveHoles) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  ReadReport read;
  const Mesh m = ReadShared("meshes/bench/stanford-bunny.obj", &read);
  EXPECT_EQ(m.num_vertices() + read.dropped_unreferenced_vertices, 35947u);
  EXPECT_EQ(read.dropped_unreferenced_vertices, 1113u);
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.boundary_edges, 223u);
  EXPECT_EQ(d.boundary_loops, 5u);
  EXPECT_EQ(d.non_manifold_edges, 0u);
  const MeshTopology topology(m);
  size_t loop_edges = 0;
  for (const BoundaryLoop& loop : topology.BoundaryLoops()) {
    EXPECT_TRUE(loop.closed);
    loop_edges += loop.edges.size();
  }
  EXPECT_EQ(loop_edges, 223u);
}

TEST(SharedMeshes, DragonRes2IsRepaired) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "no shared meshes";
  const Mesh m = ReadShared("meshes/bench/dragon_vrip_res2.ply.gz");
  const MeshDiagnosis d = Diagnose(m);
  EXPECT_EQ(d.non_manifold_edges, 2534u);
  EXPECT_EQ(d.components, 12u);                  // edge-connected
  EXPECT_EQ(d.vertex_connected_components, 7u);  // as MANIFEST.md counts them
  RepairReport report;
  ExpectRepairedClean(m, &report);
  // Stacked duplicate triangles explain part of the non-manifold edges; the
  // misoriented faces sit behind non-manifold edges (no two-face edge is
  // inconsistent before repair) and show up as flips and cuts.
  EXPECT_GT(report.duplicate_faces_removed, 0u);
  EXPECT_GT(report.non_manifold_edges_split, 0u);
  EXPECT_GT(report.faces_flipped, 0u);
}

}  // namespace
}  // namespace eqmesh

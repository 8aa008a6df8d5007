// Structural properties of the remesher's output: nesting, valences, base
// vertices taken from the input, kinds, kept components, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "mesh/mesh_topology.h"
#include "remesh/remesh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

SemiRegularMesh RemeshSphere(RemeshReport* report) {
  RemeshOptions options;
  options.levels = 2;
  options.base_vertices = 20;
  auto result = Remesh(testing::MakeIcosphere(3), options, report);
  EXPECT_TRUE(result.ok()) << result.status().ToString();
  return result.ok() ? std::move(result).value() : SemiRegularMesh();
}

TEST(RemeshStructure, BaseVerticesAreInputVertices) {
  RemeshReport report;
  const SemiRegularMesh m = RemeshSphere(&report);
  const Mesh input = testing::MakeIcosphere(3);
  std::set<std::array<double, 3>> inputs;
  for (const Vec3& p : input.positions) inputs.insert({p.x(), p.y(), p.z()});
  ASSERT_GT(m.hierarchy.NumVertices(0), 3u);
  EXPECT_EQ(report.base_vertices, m.hierarchy.NumVertices(0));
  for (uint32_t v = 0; v < m.hierarchy.NumVertices(0); ++v) {
    const Vec3& p = m.positions[v];
    EXPECT_TRUE(inputs.count({p.x(), p.y(), p.z()})) << "base vertex " << v;
    EXPECT_EQ(m.kinds[v], VertexKind::kBase);
  }
}

TEST(RemeshStructure, SubdivisionVerticesHaveValenceSix) {
  RemeshReport report;
  const SemiRegularMesh m = RemeshSphere(&report);
  const int top = m.hierarchy.levels();
  const MeshTopology t(ExtractLevel(m, top));
  for (uint32_t v = m.hierarchy.NumVertices(0); v < m.hierarchy.NumVertices(top); ++v) {
    EXPECT_EQ(t.VertexFaces(v).size(), 6u) << "vertex " << v;
  }
  EXPECT_EQ(m.positions.size(), m.hierarchy.NumVertices(top));
  EXPECT_EQ(m.kinds.size(), m.positions.size());
  for (uint32_t v = m.hierarchy.NumVertices(0); v < m.kinds.size(); ++v) {
    EXPECT_NE(m.kinds[v], VertexKind::kBase);
  }
  ASSERT_EQ(report.normal_fraction_per_level.size(), 2u);
}

TEST(RemeshStructure, DeterministicAcrossRuns) {
  RemeshReport r1, r2;
  const SemiRegularMesh a = RemeshSphere(&r1);
  const SemiRegularMesh b = RemeshSphere(&r2);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t v = 0; v < a.positions.size(); ++v) EXPECT_EQ(a.positions[v], b.positions[v]);
  EXPECT_EQ(a.hierarchy.BaseFaces(), b.hierarchy.BaseFaces());
}

TEST(RemeshStructure, TinyComponentIsKeptExactly) {
  Mesh input = testing::MakeIcosphere(3);
  const uint32_t n = static_cast<uint32_t>(input.positions.size());
  input.positions.push_back(Vec3(5, 0, 0));
  input.positions.push_back(Vec3(6, 0, 0));
  input.positions.push_back(Vec3(5, 1, 0));
  input.faces.push_back({n, n + 1, n + 2});
  RemeshOptions options;
  options.levels = 1;
  options.base_vertices = 20;
  RemeshReport report;
  auto m = Remesh(input, options, &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(report.components_remeshed, 1u);
  EXPECT_EQ(report.components_kept_exactly, 1u);
  EXPECT_EQ(report.kept_exactly_vertices, 3u);
  EXPECT_EQ(m->kept_exactly.faces.size(), 1u);
  EXPECT_EQ(ExtractLevel(*m, 1).faces.size(), m->hierarchy.Faces(1).size() + 1);
}

TEST(RemeshStructure, AutomaticLevelsStopAtAMeasuredPoint) {
  RemeshOptions options;
  options.base_vertices = 20;
  RemeshReport report;
  auto m = Remesh(testing::MakeIcosphere(2), options, &report);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_GE(report.levels, 1);
  EXPECT_EQ(report.estimated_psnr_db_per_level.size(), static_cast<size_t>(report.levels));
  EXPECT_GE(report.output_vertices, report.input_vertices);
}

}  // namespace
}  // namespace eqmesh

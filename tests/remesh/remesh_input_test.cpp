// Bad input gets a clear one-line error, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mesh_io/mesh_io.h"
#include "remesh/remesh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

Status RemeshStatus(const Mesh& input, RemeshOptions options = {}) {
  RemeshReport report;
  return Remesh(input, options, &report).status();
}

TEST(RemeshInput, EmptyMeshIsRefused) {
  const Status s = RemeshStatus(Mesh());
  EXPECT_EQ(s.code(), StatusCode::kInvalidMesh);
  EXPECT_NE(s.message().find("no faces"), std::string::npos) << s.message();
}

TEST(RemeshInput, NanCoordinateIsRefused) {
  Mesh m = testing::MakeIcosphere(1);
  m.positions[3].x() = std::numeric_limits<double>::quiet_NaN();
  const Status s = RemeshStatus(m);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("non-finite"), std::string::npos) << s.message();
}

TEST(RemeshInput, OutOfRangeIndexIsRefused) {
  Mesh m = testing::MakeIcosphere(1);
  m.faces[0][1] = 9999;
  const Status s = RemeshStatus(m);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("9999"), std::string::npos) << s.message();
}

TEST(RemeshInput, NonManifoldEdgeIsNamed) {
  Mesh m = testing::MakeIcosphere(1);
  const Face f = m.faces[0];
  const uint32_t n = static_cast<uint32_t>(m.positions.size());
  m.positions.push_back(Vec3(3, 3, 3));
  m.faces.push_back({f[0], f[1], n});  // a third face on edge f0-f1
  const Status s = RemeshStatus(m);
  EXPECT_EQ(s.code(), StatusCode::kInvalidMesh);
  EXPECT_NE(s.message().find("non-manifold edge"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("--repair"), std::string::npos) << s.message();
}

TEST(RemeshInput, BadOptionsAreRefused) {
  RemeshOptions options;
  options.levels = 42;
  EXPECT_EQ(RemeshStatus(testing::MakeIcosphere(1), options).code(), StatusCode::kInvalidArgument);
  options.levels = 1;
  options.base_vertices = 0;
  EXPECT_EQ(RemeshStatus(testing::MakeIcosphere(1), options).code(), StatusCode::kInvalidArgument);
}

TEST(RemeshInput, PinchedCowNeedsRepair) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "shared meshes absent";
  auto cow = ReadMesh(testing::SharedPath("meshes/small/cow.ply"));
  ASSERT_TRUE(cow.ok()) << cow.status().ToString();
  RemeshOptions options;
  options.levels = 1;
  const Status s = RemeshStatus(*cow, options);
  EXPECT_EQ(s.code(), StatusCode::kInvalidMesh);
  EXPECT_NE(s.message().find("non-manifold"), std::string::npos) << s.message();
  options.repair = true;
  RemeshReport report;
  auto repaired = Remesh(*cow, options, &report);
  EXPECT_TRUE(repaired.ok()) << repaired.status().ToString();
}

}  // namespace
}  // namespace eqmesh

namespace eqmesh {
namespace {

Mesh ScaledBy(Mesh mesh, double scale) {
  for (Vec3& p : mesh.positions) p *= scale;
  return mesh;
}

// The remesher works at unit scale by a power of two: the same remesh, scaled,
// at any scale. (At 1e300 squared lengths overflowed and the untangler's
// bounded searches became scans of the whole input: a hang.)
TEST(RemeshInput, ExtremeScalesRemeshExactlyAsAtUnitScale) {
  const Mesh sphere = testing::MakeIcosphere(3);
  RemeshOptions options;
  options.levels = 2;
  RemeshReport unit_report;
  auto unit = Remesh(sphere, options, &unit_report);
  ASSERT_TRUE(unit.ok()) << unit.status().ToString();
  for (const double scale : {0x1p1000, 0x1p-1000, 0x1p-3}) {
    RemeshReport report;
    auto scaled = Remesh(ScaledBy(sphere, scale), options, &report);
    ASSERT_TRUE(scaled.ok()) << scale << ": " << scaled.status().ToString();
    ASSERT_EQ(scaled->positions.size(), unit->positions.size());
    for (size_t v = 0; v < unit->positions.size(); ++v) {
      ASSERT_EQ(scaled->positions[v], unit->positions[v] * scale) << scale << " vertex " << v;
    }
    EXPECT_EQ(scaled->kinds, unit->kinds);
    EXPECT_EQ(report.normal_fraction, unit_report.normal_fraction);
  }
  RemeshReport huge_report;
  auto huge = Remesh(ScaledBy(sphere, 1e300), options, &huge_report);
  ASSERT_TRUE(huge.ok()) << huge.status().ToString();
  EXPECT_GE(huge_report.normal_fraction, 0.9);
}

TEST(RemeshInput, TriangleSoupRemeshesAsItsSurface) {
  // Flat-shaded exports give every face corners of its own: welded, the soup
  // is the torus, numbered in the same order, and remeshes exactly as it does.
  const Mesh torus = testing::MakeTorus(16, 8);
  const Mesh soup = testing::MakeTriangleSoup(torus);
  RemeshOptions options;
  options.levels = 2;
  RemeshReport torus_report, soup_report;
  auto expected = Remesh(torus, options, &torus_report);
  auto remeshed = Remesh(soup, options, &soup_report);
  ASSERT_TRUE(expected.ok()) << expected.status().ToString();
  ASSERT_TRUE(remeshed.ok()) << remeshed.status().ToString();
  EXPECT_EQ(soup_report.welded_vertices, soup.num_vertices() - torus.num_vertices());
  EXPECT_EQ(torus_report.welded_vertices, 0u);
  EXPECT_EQ(soup_report.components_remeshed, 1u);
  EXPECT_EQ(remeshed->hierarchy.BaseFaces(), expected->hierarchy.BaseFaces());
  EXPECT_EQ(remeshed->positions, expected->positions);
  EXPECT_EQ(remeshed->kinds, expected->kinds);
}

}  // namespace
}  // namespace eqmesh

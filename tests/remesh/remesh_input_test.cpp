// Bad input gets a clear one-line error, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mesh/mesh_io.h"
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

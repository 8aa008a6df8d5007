#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "mesh_io/semi_regular_io.h"
#include "test_support.h"

namespace eqmesh {
namespace {

SemiRegularMesh MakeSample() {
  const Mesh ico = testing::MakeIcosphere(0);
  SemiRegularMesh m;
  m.hierarchy = *SemiRegularHierarchy::Build(12, ico.faces, 2);
  m.positions.resize(m.hierarchy.NumVertices(2));
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const double x = static_cast<double>(i);
    m.positions[i] = Vec3(0.1 * x, 1.0 / (x + 1.0), -3.0 * x);
  }
  m.kinds.assign(m.positions.size(), VertexKind::kNormal);
  m.kinds[0] = VertexKind::kBase;
  m.kept_exactly.positions = {{1, 2, 3}, {4, 5, 6}, {7, 8, 10}};
  m.kept_exactly.faces = {{0, 1, 2}};
  return m;
}

std::string TempPath(const char* name) { return std::string(EQMESH_BINARY_DIR) + "/" + name; }

TEST(SemiRegularIo, RoundTripIsExact) {
  const SemiRegularMesh m = MakeSample();
  const std::string path = TempPath("roundtrip.srm");
  ASSERT_TRUE(WriteSemiRegular(m, path).ok());
  auto back = ReadSemiRegular(path);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->hierarchy.levels(), 2);
  EXPECT_EQ(back->positions, m.positions);
  EXPECT_EQ(back->kinds, m.kinds);
  EXPECT_EQ(back->kept_exactly.positions, m.kept_exactly.positions);
  EXPECT_EQ(back->kept_exactly.faces, m.kept_exactly.faces);
  EXPECT_EQ(back->hierarchy.Faces(2), m.hierarchy.Faces(2));
}

TEST(SemiRegularIo, EveryTruncationIsAnError) {
  const std::string path = TempPath("truncate.srm");
  ASSERT_TRUE(WriteSemiRegular(MakeSample(), path).ok());
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = TempPath("truncated.srm");
  for (size_t n = 0; n < bytes.size(); n += 7) {
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(n));
    EXPECT_FALSE(ReadSemiRegular(cut).ok()) << n;
  }
  std::ofstream(cut, std::ios::binary) << bytes << "x";
  EXPECT_FALSE(ReadSemiRegular(cut).ok());
  EXPECT_EQ(ReadSemiRegular(TempPath("missing.srm")).status().code(), StatusCode::kIoError);
}

}  // namespace
}  // namespace eqmesh

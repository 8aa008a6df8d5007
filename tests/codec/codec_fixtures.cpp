#include "codec_fixtures.h"

#include <gtest/gtest.h>

#include "coding/decoder.h"

#include <cmath>
#include <fstream>
#include <iterator>

#include "test_support.h"

namespace eqmesh::testing {

SemiRegularMesh MakeBumpySphere(int levels) {
  const Mesh ico = MakeIcosphere(0);
  SemiRegularMesh mesh;
  mesh.hierarchy = SemiRegularHierarchy::Build(static_cast<uint32_t>(ico.positions.size()),
                                               ico.faces, levels).value();
  const SemiRegularHierarchy& h = mesh.hierarchy;
  // Positions level by level: odd vertex = edge midpoint pushed to the surface.
  std::vector<Vec3> p = ico.positions;
  for (int j = 0; j < levels; ++j) {
    for (uint32_t k = 0; k < h.NumOddVertices(j); ++k) {
      const Edge& e = h.OddEdge(j, k);
      p.push_back((0.5 * (p[e[0]] + p[e[1]])).normalized());
    }
  }
  for (Vec3& v : p) {
    const Vec3 u = v.normalized();
    v = u * (1.0 + 0.1 * std::sin(3.0 * u.x()) * std::cos(2.0 * u.y()));
  }
  mesh.positions = std::move(p);
  return mesh;
}

SemiRegularMesh MakeBumpySphereWithKept(int levels) {
  SemiRegularMesh mesh = MakeBumpySphere(levels);
  mesh.kept_exactly.positions = {Vec3(2, 0, 0), Vec3(2.1, 0, 0), Vec3(2, 0.1, 0), Vec3(2, 0, 0.1)};
  mesh.kept_exactly.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

SemiRegularMesh MakeBumpySphereWithCreases(int levels) {
  SemiRegularMesh mesh = MakeBumpySphere(levels);
  const Face& f = mesh.hierarchy.BaseFaces()[0];
  EXPECT_TRUE(mesh.hierarchy.SetBaseCreases({{f[0], f[1]}, {f[1], f[2]}, {f[2], f[0]}}).ok());
  return mesh;
}

EncodeOptions GoldenOptions() {
  EncodeOptions options;
  options.transform = bitstream::TransformId::kUnlifted;
  options.coder = bitstream::CoderId::kEq;
  options.lambda = 1.0 / 16.0;
  options.tangential_factor = 100.0;
  return options;
}

std::string GoldenPath() {
  return std::string(EQMESH_SOURCE_DIR) + "/tests/codec/data/golden_v1_5.eqm";
}

SemiRegularMesh MakeAsIsSphere() {
  const SemiRegularMesh refined = MakeBumpySphere(3);
  const Mesh finest = ExtractLevel(refined, 3);
  SemiRegularMesh mesh;
  mesh.hierarchy = SemiRegularHierarchy::Build(static_cast<uint32_t>(finest.positions.size()), finest.faces, 0).value();
  mesh.positions = finest.positions;
  return mesh;
}

std::string AsIsGoldenPath() {
  return std::string(EQMESH_SOURCE_DIR) + "/tests/codec/data/golden_v1_6_as_is.eqm";
}

std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

double MaxVertexError(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

}  // namespace eqmesh::testing

namespace eqmesh::testing {
double MaxNearestDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (const Vec3& p : a) {
    double best = 1e300;
    for (const Vec3& q : b) best = std::min(best, (p - q).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}
}  // namespace eqmesh::testing

namespace eqmesh::testing {
double Diagonal(const std::vector<Vec3>& points) {
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}
}  // namespace eqmesh::testing

namespace eqmesh::testing {

void ExpectEachMaxLevelGivesItsCounts(const std::vector<uint8_t>& bytes, const SemiRegularMesh& mesh) {
  const int levels = mesh.hierarchy.levels();
  const size_t kept_v = mesh.kept_exactly.positions.size(), kept_f = mesh.kept_exactly.faces.size();
  for (int k = 0; k <= levels + 1; ++k) {
    DecodeOptions options;
    options.max_level = k;
    DecodeInfo info;
    auto decoded = Decode(bytes.data(), bytes.size(), options, &info);
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    const int level = std::min(k, levels);
    EXPECT_EQ(info.levels_decoded, level);
    EXPECT_EQ(decoded->positions.size(), mesh.hierarchy.NumVertices(level) + kept_v);
    EXPECT_EQ(decoded->faces.size(), mesh.hierarchy.Faces(level).size() + kept_f);
  }
}

}  // namespace eqmesh::testing

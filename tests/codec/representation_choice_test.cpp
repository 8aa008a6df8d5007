// Representation choice (coding/representation_choice.h): a low-poly mesh travels
// as is when that is smaller, still meets its PSNR target and keeps its own
// triangles; as is is tried only where its connectivity and positions could fit;
// the as-is mesh holds every component in its base and is the input itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/representation_choice.h"
#include "metrics/surface_distance.h"
#include "remesh/remesh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// An icosphere with each vertex pushed out by up to 20 %: flat facets, sharp
// creases, nothing a subdivision surface predicts.
Mesh Gem() {
  Mesh m = testing::MakeIcosphere(1);
  uint32_t state = 99;
  for (Vec3& p : m.positions) {
    state = state * 1664525u + 1013904223u;
    p *= 1.0 + 0.2 * static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  }
  return m;
}

// The gem's normal mesh with one level: a short level search, since the tests are
// about the choice, not the remesh.
SemiRegularMesh OneLevelRemesh(const Mesh& gem) {
  RemeshOptions remesh;
  remesh.levels = 1;
  RemeshReport report;
  auto remeshed = Remesh(gem, remesh, &report);
  EXPECT_TRUE(remeshed.ok()) << remeshed.status().ToString();
  return remeshed.ok() ? *std::move(remeshed) : SemiRegularMesh();
}

// A PSNR target on `gem`, measured at 20k samples: the choice, not the meter's
// precision, is under test.
EncodeOptions PsnrTarget(const Mesh& gem, double psnr) {
  EncodeOptions options;
  options.original = &gem;
  options.input_vertices = gem.positions.size();
  options.target_psnr = psnr;
  options.psnr_samples = 20'000;
  return options;
}

TEST(RepresentationChoice, AsIsMeshHoldsEveryComponentInItsBase) {
  // A small tetrahedron: a component the remesher sets aside (kept_exactly).
  Mesh tetrahedron;
  tetrahedron.positions = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, 0, 0.1)};
  tetrahedron.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const Mesh mesh = testing::WithComponent(testing::MakeIcosphere(2), tetrahedron, Vec3(3, 0, 0));
  auto as_is = AsIsMesh(mesh, false);
  ASSERT_TRUE(as_is.ok()) << as_is.status().ToString();
  EXPECT_EQ(as_is->hierarchy.levels(), 0);
  EXPECT_TRUE(as_is->kept_exactly.faces.empty());
  EXPECT_EQ(as_is->positions.size(), mesh.positions.size());
  EXPECT_EQ(as_is->hierarchy.BaseFaces().size(), mesh.faces.size());
}

// Each face as its three corners, turned to start at the smallest (orientation kept).
std::multiset<std::array<std::array<double, 3>, 3>> FaceCorners(const Mesh& m) {
  std::multiset<std::array<std::array<double, 3>, 3>> out;
  for (const Face& f : m.faces) {
    std::array<std::array<double, 3>, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = {m.positions[f[i]].x(), m.positions[f[i]].y(), m.positions[f[i]].z()};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

// A spike on a face of a sphere: a valence-3 tip, where the remesher's base
// flips an edge for its refinement. The as-is representation has no
// refinement and must be the input itself.
TEST(RepresentationChoice, AsIsMeshIsTheInputAtValenceThreeTips) {
  Mesh mesh = testing::MakeIcosphere(2);
  const Face split = mesh.faces.back();
  mesh.faces.pop_back();
  const Vec3 centroid = (mesh.positions[split[0]] + mesh.positions[split[1]] + mesh.positions[split[2]]) / 3.0;
  const uint32_t tip = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.push_back(1.6 * centroid);
  mesh.faces.push_back({split[0], split[1], tip});
  mesh.faces.push_back({split[1], split[2], tip});
  mesh.faces.push_back({split[2], split[0], tip});
  auto as_is = AsIsMesh(mesh, false);
  ASSERT_TRUE(as_is.ok()) << as_is.status().ToString();
  EXPECT_TRUE(FaceCorners(ExtractLevel(*as_is, 0)) == FaceCorners(mesh));
}

TEST(RepresentationChoice, LowPolyMeshTravelsAsIsAndMeetsItsTarget) {
  const Mesh gem = Gem();
  const SemiRegularMesh normal_mesh = OneLevelRemesh(gem);
  ASSERT_FALSE(normal_mesh.positions.empty());
  const EncodeOptions options = PsnrTarget(gem, 55.0);
  EncodeReport report;
  RepresentationReport choice;
  RepresentationOptions allowed;
  allowed.allow_as_is = true;
  auto stream = EncodeChoosingRepresentation(normal_mesh, options, allowed, &report, nullptr, &choice);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  ASSERT_TRUE(choice.tried_as_is);
  EXPECT_TRUE(choice.as_is);
  EXPECT_EQ(stream->size(), choice.as_is_bytes);
  if (choice.remeshed_bytes > 0) {
    EXPECT_LT(choice.as_is_bytes, choice.remeshed_bytes);
  }
  auto decoded = Decode(stream->data(), stream->size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->faces.size(), gem.faces.size());  // the artist's triangles, no more
  CompareOptions compare;
  compare.samples = options.psnr_samples;
  auto distance = CompareSurfaces(gem, *decoded, compare);
  ASSERT_TRUE(distance.ok());
  EXPECT_GE(distance->psnr_db, 55.0);
  EXPECT_DOUBLE_EQ(distance->psnr_db, report.psnr_db);
  // Not allowed (an explicit level count, say): the normal mesh is kept.
  RepresentationReport kept;
  auto normal = EncodeChoosingRepresentation(normal_mesh, options, RepresentationOptions{}, nullptr, nullptr, &kept);
  // The one-level normal mesh of this gem may not reach 55 dB at all.
  if (!normal.ok()) {
    EXPECT_EQ(normal.status().code(), StatusCode::kTargetOutOfReach);
  }
  EXPECT_FALSE(kept.tried_as_is);
  EXPECT_FALSE(kept.as_is);
}

TEST(RepresentationChoice, ATargetNeitherReachesNamesTheBestOfEach) {
  const Mesh gem = Gem();
  const SemiRegularMesh normal_mesh = OneLevelRemesh(gem);
  ASSERT_FALSE(normal_mesh.positions.empty());
  const EncodeOptions options = PsnrTarget(gem, 250.0);
  RepresentationOptions allowed;
  allowed.allow_as_is = true;
  auto stream = EncodeChoosingRepresentation(normal_mesh, options, allowed, nullptr, nullptr, nullptr);
  ASSERT_FALSE(stream.ok());
  EXPECT_EQ(stream.status().code(), StatusCode::kTargetOutOfReach);
  const std::string& m = stream.status().message();
  EXPECT_NE(m.find("out of reach"), std::string::npos) << m;
  EXPECT_NE(m.find("; coded as is, "), std::string::npos) << m;
  EXPECT_EQ(m.find("coded as is, the remesh"), std::string::npos) << m;  // the as-is side has no remesh
}

TEST(RepresentationChoice, AsIsIsOnlyTriedWhereItsConnectivityAndPositionsFit) {
  // The bumpy sphere's 642 vertices coded as is need their connectivity (2-3 bits
  // per vertex here) plus kAsIsMinPositionBits each: a stream of 4 bits per vertex
  // leaves no room, one of 12 does.
  const SemiRegularMesh refined = testing::MakeBumpySphere(3);
  auto as_is = AsIsMesh(ExtractLevel(refined, 3), false);
  ASSERT_TRUE(as_is.ok()) << as_is.status().ToString();
  const size_t vertices = as_is->positions.size();
  EXPECT_FALSE(AsIsFitsIn(*as_is, vertices * 4 / 8));
  EXPECT_TRUE(AsIsFitsIn(*as_is, vertices * 12 / 8));
}

}  // namespace
}  // namespace eqmesh

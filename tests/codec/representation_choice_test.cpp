// Representation choice (coding/representation_choice.h): a low-poly mesh travels
// as is when that is smaller, still meets its PSNR target and keeps its own
// triangles; as is is tried only where its connectivity and positions could fit;
// the as-is mesh holds every component in its base and is the input itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <set>
#include <string>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/representation_choice.h"
#include "metrics/surface_distance.h"
#include "remesh/quadric_simplification.h"
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

// Options that measure against `original` at 20k samples: the choice, not the
// meter's precision, is under test.
EncodeOptions MeasuredAgainst(const Mesh& original) {
  EncodeOptions options;
  options.original = &original;
  options.input_vertices = original.positions.size();
  options.psnr_samples = 20'000;
  return options;
}

// A .glb primitive's default: a bare lambda, measured within the input's own
// triangle count, above a floor, the input allowed to travel as is.
struct GlbDefault {
  EncodeOptions options;
  RepresentationOptions allowed;
};
GlbDefault GlbDefaultFor(const Mesh& mesh) {
  GlbDefault d{MeasuredAgainst(mesh), RepresentationOptions()};
  d.options.measure_psnr = true;
  d.options.max_triangles = mesh.faces.size();
  d.allowed.allow_as_is = true;
  d.allowed.floor_db = 20.0;
  return d;
}

EncodeOptions PsnrTarget(const Mesh& gem, double psnr) {
  EncodeOptions options = MeasuredAgainst(gem);
  options.target_psnr = psnr;
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
  EXPECT_LE(decoded->faces.size(), gem.faces.size());  // the artist's triangles, no more
  EXPECT_LE(choice.as_is_vertices, gem.positions.size());
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

// A torus whose vertices are moved at random along its surface (within its
// tangent planes, by up to a third of an edge): an irregular tessellation, as
// a modeller's or a scanner's is, of a smooth shape.
Mesh JitteredTorus(int n, int m_around) {
  Mesh m = testing::MakeTorus(n, m_around);
  uint32_t state = 7;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
  };
  const double edge = 2.0 * M_PI * 0.35 / m_around;
  for (Vec3& p : m.positions) {
    const Vec3 centre = Vec3(p.x(), p.y(), 0.0).normalized();
    const Vec3 normal = (p - centre).normalized();
    const Vec3 around = Vec3(-p.y(), p.x(), 0.0).normalized();
    const Vec3 along = normal.cross(around);
    p += (2.0 / 3.0) * edge * (uniform() * around + uniform() * along);
  }
  return m;
}

// An irregular tessellation with more vertices than a 60 dB target needs (a
// jittered torus, itself simplified for irregular valences): with a target the
// as-is representation is also tried simplified, and the simplified stream
// wins: fewer vertices and bytes than the input as is, the target still met on
// the decoded mesh. (On a regular grid the as-is coder's parallelograms predict
// every vertex, and a simplification that breaks the grid costs more.)
TEST(RepresentationChoice, IrregularMeshTravelsSimplifiedWhereThatIsSmaller) {
  auto irregular = SimplifyByQuadrics(JitteredTorus(64, 32), 1500);
  ASSERT_TRUE(irregular.ok());
  const Mesh gem = *irregular;
  const SemiRegularMesh normal_mesh = OneLevelRemesh(gem);
  ASSERT_FALSE(normal_mesh.positions.empty());
  const EncodeOptions options = PsnrTarget(gem, 60.0);
  RepresentationOptions allowed;
  allowed.allow_as_is = true;
  EncodeReport report;
  RepresentationReport choice;
  auto stream = EncodeChoosingRepresentation(normal_mesh, options, allowed, &report, nullptr, &choice);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  ASSERT_TRUE(choice.as_is);
  EXPECT_LT(choice.as_is_vertices, gem.positions.size() * 3 / 4);
  auto as_is_mesh = AsIsMesh(gem, false);
  ASSERT_TRUE(as_is_mesh.ok());
  auto unsimplified = EncodeChoosingLevels(*as_is_mesh, options, nullptr, nullptr);
  ASSERT_TRUE(unsimplified.ok());
  EXPECT_LT(stream->size(), unsimplified->size());
  auto decoded = Decode(stream->data(), stream->size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->positions.size(), choice.as_is_vertices);
  CompareOptions compare;
  compare.samples = options.psnr_samples;
  auto distance = CompareSurfaces(gem, *decoded, compare);
  ASSERT_TRUE(distance.ok());
  EXPECT_GE(distance->psnr_db, 60.0);
}

// Without a target too: where the as-is stream at the caller's lambda wins, it
// is simplified where that keeps its PSNR in fewer bytes.
TEST(RepresentationChoice, WithoutATargetTheAsIsStreamIsSimplifiedToo) {
  // A .glb primitive's default (a bare lambda, within the input's own triangle
  // count, above a floor), on an irregular mesh with more vertices than its
  // quality needs: the two-level normal mesh within that count is beaten by the
  // input as is searched for its PSNR, and more so by the input simplified.
  auto irregular = SimplifyByQuadrics(JitteredTorus(64, 32), 1500);
  ASSERT_TRUE(irregular.ok());
  const Mesh mesh = *irregular;
  RemeshOptions two;
  two.levels = 2;
  auto normal_mesh = Remesh(mesh, two, nullptr);
  ASSERT_TRUE(normal_mesh.ok());
  GlbDefault glb = GlbDefaultFor(mesh);
  glb.options.lambda = 1.0;
  EncodeReport report;
  RepresentationReport choice;
  auto stream = EncodeChoosingRepresentation(*normal_mesh, glb.options, glb.allowed, &report, nullptr, &choice);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  ASSERT_TRUE(choice.as_is);
  EXPECT_LT(choice.as_is_vertices, mesh.positions.size());
  EXPECT_LE(choice.as_is_bytes, choice.remeshed_bytes);
  EXPECT_GE(choice.as_is_psnr_db, choice.remeshed_psnr_db);
  auto decoded = Decode(stream->data(), stream->size());
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->positions.size(), choice.as_is_vertices);
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

TEST(RepresentationChoice, WithoutATargetAsIsReplacesAStreamItBeatsOnBothCounts) {
  // A .glb primitive's default: a bare lambda, measured within the input's own
  // triangle count, above a floor. The gem's one-level remesh cut to the gem's 80
  // triangles cannot follow its facets; the gem as is can, in fewer bytes.
  const Mesh gem = Gem();
  const SemiRegularMesh normal_mesh = OneLevelRemesh(gem);
  ASSERT_FALSE(normal_mesh.positions.empty());
  auto [options, allowed] = GlbDefaultFor(gem);
  RepresentationReport choice;
  EncodeReport report;
  auto stream = EncodeChoosingRepresentation(normal_mesh, options, allowed, &report, nullptr, &choice);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  ASSERT_TRUE(choice.tried_as_is);
  ASSERT_GE(choice.remeshed_psnr_db, allowed.floor_db);
  EXPECT_TRUE(choice.as_is);
  EXPECT_LE(choice.as_is_bytes, choice.remeshed_bytes);
  EXPECT_GE(choice.as_is_psnr_db, choice.remeshed_psnr_db);
  EXPECT_EQ(stream->size(), choice.as_is_bytes);
  // Without a floor, and without the caller asking for a measurement (an .eqm
  // stream at a bare lambda), the two are measured for the comparison all the same.
  allowed.floor_db = 0;
  options.measure_psnr = false;
  RepresentationReport unasked;
  auto same = EncodeChoosingRepresentation(normal_mesh, options, allowed, nullptr, nullptr, &unasked);
  ASSERT_TRUE(same.ok()) << same.status().ToString();
  EXPECT_TRUE(unasked.as_is);
  EXPECT_EQ(*same, *stream);
  EXPECT_EQ(unasked.remeshed_psnr_db, choice.remeshed_psnr_db);
}

TEST(RepresentationChoice, MeshTooSmallToRemeshTravelsAsIs) {
  // Every component below the remesher's minimum: there is no normal mesh to
  // code, with or without a target, and the input itself is what travels.
  Mesh tetrahedron;
  tetrahedron.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tetrahedron.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  RemeshReport remesh_report;
  auto remeshed = Remesh(tetrahedron, RemeshOptions{}, &remesh_report);
  ASSERT_TRUE(remeshed.ok()) << remeshed.status().ToString();
  ASSERT_EQ(remeshed->hierarchy.NumVertices(0), 0u);
  RepresentationOptions allowed;
  allowed.allow_as_is = true;
  for (const double target : {0.0, 70.0}) {
    EncodeOptions options = MeasuredAgainst(tetrahedron);
    options.target_psnr = target;
    RepresentationReport choice;
    auto stream = EncodeChoosingRepresentation(*remeshed, options, allowed, nullptr, nullptr, &choice);
    ASSERT_TRUE(stream.ok()) << target << ": " << stream.status().ToString();
    EXPECT_TRUE(choice.as_is);
    EXPECT_EQ(choice.remeshed_bytes, 0u);
    auto decoded = Decode(stream->data(), stream->size());
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    EXPECT_EQ(decoded->faces.size(), tetrahedron.faces.size());
    EXPECT_TRUE(choice.nothing_remeshed);
  }
  // A target beyond the input as is: out of reach, saying what as is reached (not
  // that nothing was remeshed, which is no reason once as is may travel).
  // (Corners off every grid: the integer corners above are coded exactly.)
  Mesh skewed = tetrahedron;
  for (Vec3& p : skewed.positions) p += Vec3(std::sqrt(2.0), std::sqrt(3.0), std::sqrt(5.0)) * (0.1 + p.sum() / 7.0);
  auto skewed_remesh = Remesh(skewed, RemeshOptions{}, &remesh_report);
  ASSERT_TRUE(skewed_remesh.ok()) << skewed_remesh.status().ToString();
  EncodeOptions too_high = MeasuredAgainst(skewed);
  too_high.target_psnr = 300.0;
  auto unreachable = EncodeChoosingRepresentation(*skewed_remesh, too_high, allowed, nullptr, nullptr, nullptr);
  ASSERT_FALSE(unreachable.ok());
  EXPECT_EQ(unreachable.status().code(), StatusCode::kTargetOutOfReach) << unreachable.status().ToString();
  // Not allowed: the encoder says why it cannot code it.
  EncodeOptions options;
  options.original = &tetrahedron;
  auto refused = EncodeChoosingRepresentation(*remeshed, options, RepresentationOptions{}, nullptr, nullptr, nullptr);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("nothing was remeshed"), std::string::npos);
}

TEST(RepresentationChoice, WithoutATargetARemeshSmallerAtItsQualityStays) {
  // A smooth sphere refined three times codes far below its 642 vertices as is,
  // so as is is either not tried (it cannot fit) or larger at the same quality.
  const SemiRegularMesh refined = testing::MakeBumpySphere(3);
  const Mesh surface = ExtractLevel(refined, 3);
  EncodeOptions options = MeasuredAgainst(surface);
  options.measure_psnr = true;
  RepresentationOptions allowed;
  allowed.allow_as_is = true;
  allowed.floor_db = 20.0;
  RepresentationReport choice;
  auto stream = EncodeChoosingRepresentation(refined, options, allowed, nullptr, nullptr, &choice);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  EXPECT_FALSE(choice.as_is);
  EXPECT_EQ(stream->size(), choice.remeshed_bytes);
  if (choice.tried_as_is && choice.as_is_bytes > 0) {
    EXPECT_GT(choice.as_is_bytes, choice.remeshed_bytes);
    EXPECT_GE(choice.as_is_psnr_db, choice.remeshed_psnr_db);
  }
}

}  // namespace
}  // namespace eqmesh

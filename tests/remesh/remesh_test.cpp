// Remesher quality on synthetic shapes and small scans: normal share, error,
// topology kept, no folds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "mesh_io/mesh_io.h"
#include "remesh/quality_checks.h"
#include "remesh/remesh.h"
#include "remesh_checks.h"
#include "test_support.h"

namespace eqmesh {
namespace {

struct RemeshRun {
  SemiRegularMesh mesh;
  RemeshReport report;
};

RemeshRun RemeshOrDie(const Mesh& input, int levels, int base_vertices) {
  RemeshOptions options;
  options.levels = levels;
  options.base_vertices = base_vertices;
  RemeshRun run;
  auto result = Remesh(input, options, &run.report);
  EXPECT_TRUE(result.ok()) << result.status().ToString();
  if (result.ok()) run.mesh = std::move(result).value();
  return run;
}

void ExpectClosedGenus(const SemiRegularMesh& m, int64_t euler) {
  for (int level = 0; level <= m.hierarchy.levels(); ++level) {
    const testing::LevelTopology t = testing::CheckLevelTopology(ExtractLevel(m, level));
    EXPECT_TRUE(t.manifold) << "level " << level;
    EXPECT_EQ(t.boundary_edges, 0u) << "level " << level;
    EXPECT_EQ(t.euler, euler) << "level " << level;
  }
}

TEST(Remesh, IcosphereIsNormalAccurateAndGenusZero) {
  const Mesh input = testing::MakeIcosphere(3);
  const RemeshRun run = RemeshOrDie(input, 3, 24);
  EXPECT_EQ(run.report.levels, 3);
  EXPECT_GE(run.report.normal_fraction, 0.95);
  ExpectClosedGenus(run.mesh, 2);
  const Mesh finest = ExtractLevel(run.mesh, 3);
  EXPECT_GT(testing::VertexPsnrDb(input, finest), 55.0);
  EXPECT_LT(testing::MaxVertexDistance(finest, input), 1e-9);  // vertices lie on the input
  EXPECT_EQ(testing::CountFlips(finest, input).flipped, 0u);
}

// The root of each vertex's connected part of `m` (union-find over its faces).
std::vector<uint32_t> ConnectedPartRoots(const Mesh& m) {
  std::vector<uint32_t> root(m.positions.size());
  for (uint32_t v = 0; v < root.size(); ++v) root[v] = v;
  const auto find = [&](uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  for (const Face& f : m.faces) {
    root[find(f[1])] = find(f[0]);
    root[find(f[2])] = find(f[0]);
  }
  for (uint32_t v = 0; v < root.size(); ++v) root[v] = find(v);
  return root;
}

// Two spheres passing through each other at a shallow angle, as parts of an
// asset often do: around the intersection curve the other sphere lies within a
// piercing's reach and nearer some face centroids than the part's own surface.
// Each part's remesh still covers its own sphere and faces out of it.
TEST(Remesh, InterpenetratingPartsEachRemeshOntoTheirOwnSurface) {
  const Vec3 centre_b(0.05, 0.0, 0.0);
  const double radius_b = 0.98;
  Mesh input = testing::MakeIcosphere(3);
  const Mesh b = testing::MakeIcosphere(3, radius_b);
  const uint32_t offset = static_cast<uint32_t>(input.positions.size());
  for (const Vec3& p : b.positions) input.positions.push_back(p + centre_b);
  for (const Face& f : b.faces) input.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  RemeshReport report;
  auto result = Remesh(input, RemeshOptions(), &report);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  const Mesh finest = ExtractLevel(*result, report.levels);
  // Every input vertex is covered by its part's remesh (a part remeshed partly
  // onto the other leaves its own surface 0.006 away there).
  EXPECT_LT(testing::MaxVertexDistance(input, finest), 0.003);
  // Which sphere each part of the remesh covers: the one most of its vertices
  // are nearer to; each face faces out of it.
  const std::vector<uint32_t> root = ConnectedPartRoots(finest);
  std::map<uint32_t, int> votes_b;
  for (uint32_t v = 0; v < root.size(); ++v) {
    const Vec3& p = finest.positions[v];
    votes_b[root[v]] += std::abs((p - centre_b).norm() - radius_b) < std::abs(p.norm() - 1.0) ? 1 : -1;
  }
  ASSERT_EQ(votes_b.size(), 2u);
  ASSERT_NE(votes_b.begin()->second > 0, votes_b.rbegin()->second > 0);
  for (const Face& f : finest.faces) {
    const Vec3& p0 = finest.positions[f[0]];
    const Vec3& p1 = finest.positions[f[1]];
    const Vec3& p2 = finest.positions[f[2]];
    const Vec3 centre = votes_b[root[f[0]]] > 0 ? centre_b : Vec3::Zero();
    EXPECT_GT((p1 - p0).cross(p2 - p0).dot((p0 + p1 + p2) / 3.0 - centre), 0.0);
  }
  const StatusOr<FoldReport> folds = CountFoldsAgainstInput(finest, input);
  ASSERT_TRUE(folds.ok());
  EXPECT_EQ(folds->flipped_faces, 0u);
  EXPECT_EQ(folds->degenerate_faces, 0u);
}

// The twelve valence-5 vertices of an icosphere pulled out into spikes: the
// base keeps the tips, none of them at valence 3 (the base domain flips an edge
// opposite such a tip: on the bench scans they seeded the folds no untangling
// removed), and the remesh keeps the genus.
TEST(Remesh, SpikeTipsAreNotLeftAtValenceThree) {
  Mesh input = testing::MakeIcosphere(3);
  for (uint32_t v = 0; v < 12; ++v) input.positions[v] *= 1.8;
  const RemeshRun run = RemeshOrDie(input, 3, 24);
  ExpectClosedGenus(run.mesh, 2);
  const Mesh base = ExtractLevel(run.mesh, 0);
  std::vector<int> valence(base.positions.size(), 0);
  for (const Face& f : base.faces) {
    for (uint32_t v : f) ++valence[v];
  }
  for (uint32_t v = 0; v < base.positions.size(); ++v) {
    if (valence[v] == 3) {
      EXPECT_GE(AngleSumAt(base, v), 300.0 * M_PI / 180.0) << "base vertex " << v;
    }
  }
  // Known gap, as on the torus: 4 of 2,816 faces fold today (session 16, tips
  // flipped below 300 degrees; 7 with the 200-degree limit of session 15, 3
  // before the placement repair looked at slivers, 1 without the tip flips,
  // which then leave 7 tips at valence 3); the test holds the line at 0.2 %.
  const Mesh finest = ExtractLevel(run.mesh, 3);
  EXPECT_LE(testing::CountFlips(finest, input).flipped, finest.faces.size() * 2 / 1000);
  // 54.3 dB today (53.6 at the 200-degree limit, 55.1 without the flips): a
  // broken remap of the flipped faces' input vertices would drop it far lower.
  EXPECT_GT(testing::VertexPsnrDb(input, finest), 50.0);
}

TEST(Remesh, TorusKeepsGenusOne) {
  const Mesh input = testing::MakeTorus(40, 20);
  const RemeshRun run = RemeshOrDie(input, 3, 40);
  EXPECT_GE(run.report.normal_fraction, 0.9);
  ExpectClosedGenus(run.mesh, 0);
  const Mesh finest = ExtractLevel(run.mesh, 3);
  EXPECT_GT(testing::VertexPsnrDb(input, finest), 50.0);
  // Known gap: a few folds survive near the torus's saddles (2 of 3840 faces
  // today); the bar is zero, the test holds the line at 0.2 %.
  EXPECT_LE(testing::CountFlips(finest, input).flipped, finest.faces.size() / 500);
}

TEST(Remesh, BumpedDiscKeepsItsBoundaryOnTheInputBoundary) {
  Mesh input = testing::MakeDisc(12);
  for (Vec3& p : input.positions) p.z() = 0.3 * std::exp(-4.0 * p.squaredNorm());
  const RemeshRun run = RemeshOrDie(input, 3, 20);
  EXPECT_EQ(run.report.boundary_loops, 1u);
  const Mesh finest = ExtractLevel(run.mesh, 3);
  const testing::LevelTopology t = testing::CheckLevelTopology(finest);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.boundary_loops, 1u);
  EXPECT_EQ(t.euler, 1);
  // Boundary vertices sit on the input's boundary polyline.
  Mesh boundary_points;
  for (size_t v = 0; v < run.mesh.kinds.size(); ++v) {
    if (run.mesh.kinds[v] == VertexKind::kBoundary) boundary_points.positions.push_back(run.mesh.positions[v]);
  }
  ASSERT_FALSE(boundary_points.positions.empty());
  EXPECT_LT(testing::MaxVertexDistance(boundary_points, input), 1e-9);
  EXPECT_GE(run.report.normal_fraction, 0.85);
}

// At the default (measured) level count, where the normal-share bar
// applies: the coarsest levels of an 8-vertex base are mostly parametric.
// max_sliver_share: of the finest faces below kSliverQuality, more than the
// placement repair leaves and less than the remesh without its sliver repair
// (session 16, tip flips up to 300 degrees: bunny_npm 1.22 %, 2.44 % without;
// rocker-arm 0.10 %, 0.24 % without).
void CheckSharedMesh(const std::string& name, int64_t euler, double min_normal, double max_sliver_share) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "shared meshes absent";
  auto input = ReadMesh(testing::SharedPath("meshes/small/" + name));
  ASSERT_TRUE(input.ok()) << input.status().ToString();
  const RemeshRun run = RemeshOrDie(*input, -1, -1);
  EXPECT_GE(run.report.levels, 4) << name;
  EXPECT_GE(run.report.normal_fraction, min_normal) << name;
  // The base is sized by the shape, but stays a small fraction of the input.
  EXPECT_LE(run.report.base_vertices, input->positions.size() / 10) << name;
  ExpectClosedGenus(run.mesh, euler);
  const Mesh finest = ExtractLevel(run.mesh, run.mesh.hierarchy.levels());
  EXPECT_LE(static_cast<double>(CountSlivers(finest)), max_sliver_share * static_cast<double>(finest.faces.size()))
      << name;
}

// Largest distance of a point set to the segments of the input's boundary edges
// (brute force: a test-sized boundary).
double MaxDistanceToBoundaryEdges(const std::vector<Vec3>& points, const Mesh& input) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const Face& f : input.faces) {
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(f[c], f[(c + 1) % 3])];
  }
  // Only the boundary edges, gathered once: scanning the whole edge map per
  // point made this test the slowest of the suite (26 s, minutes under ASan).
  std::vector<std::pair<uint32_t, uint32_t>> boundary_edges;
  for (const auto& [edge, count] : uses) {
    if (count == 1) boundary_edges.push_back(edge);
  }
  double worst = 0.0;
  for (const Vec3& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& edge : boundary_edges) {
      const Vec3 a = input.positions[edge.first], d = input.positions[edge.second] - a;
      const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * d - p).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

// The untangler slides boundary vertices along the holes: they must
// stay on the input's boundary curves, the holes stay holes.
TEST(Remesh, StanfordBunnyBoundaryVerticesStayOnItsHoles) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "shared meshes absent";
  auto input = ReadMesh(testing::SharedPath("meshes/bench/stanford-bunny.obj"));
  ASSERT_TRUE(input.ok()) << input.status().ToString();
  // Four levels, not the automatic six: the fourth is already refined in 3D and
  // untangled by the final pass, which lets boundary vertices slide, with a
  // sixteenth of the vertices (Release: 2.0 s, against 13.6 s at six levels).
  const RemeshRun run = RemeshOrDie(*input, 4, -1);
  ASSERT_EQ(run.mesh.hierarchy.levels(), 4);
  EXPECT_EQ(run.report.boundary_loops, 5u);
  const testing::LevelTopology t = testing::CheckLevelTopology(ExtractLevel(run.mesh, run.mesh.hierarchy.levels()));
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.boundary_loops, 5u);
  std::vector<Vec3> boundary;
  for (size_t v = 0; v < run.mesh.kinds.size(); ++v) {
    if (run.mesh.kinds[v] == VertexKind::kBoundary) boundary.push_back(run.mesh.positions[v]);
  }
  ASSERT_FALSE(boundary.empty());
  EXPECT_LT(MaxDistanceToBoundaryEdges(boundary, *input), 1e-9 * BoundingBoxDiagonal(*input));
  EXPECT_GE(run.report.normal_fraction, 0.9);
}

// Where the automatic level count still folds after the fold retries (cow:
// 24 faces at 5 levels on a 189-vertex base), the remesher tries a level fewer,
// on the finer base its floor then asks for, and keeps it only for fewer folds
// above the floor, as dense as the input where the input is densest. Plain
// build only (scripts/test-sanitizers.sh): the first Remesh() call alone remeshes
// the 2,904-vertex asset several times over (its drops, each with floor and retries).
TEST(Remesh, ALevelFewerWhereTheAutomaticCountFolds) {
  if (!testing::HaveSharedMeshes()) GTEST_SKIP() << "shared meshes absent";
  auto cow = ReadMesh(testing::SharedPath("meshes/midsize/cow.off.gz"));
  ASSERT_TRUE(cow.ok()) << cow.status().ToString();
  RemeshOptions options;
  options.min_psnr = kRemeshQualityFloorDb;
  RemeshReport fewer;
  auto kept = Remesh(*cow, options, &fewer);
  ASSERT_TRUE(kept.ok()) << kept.status().ToString();
  options.levels = fewer.levels + 1;
  RemeshReport more;
  auto finer = Remesh(*cow, options, &more);
  ASSERT_TRUE(finer.ok()) << finer.status().ToString();
  const size_t kept_flips = testing::CountFlips(ExtractLevel(*kept, fewer.levels), *cow).flipped;
  const size_t finer_flips = testing::CountFlips(ExtractLevel(*finer, more.levels), *cow).flipped;
  EXPECT_LT(kept_flips, finer_flips);
  EXPECT_GE(fewer.psnr_db, kRemeshQualityFloorDb);
  EXPECT_GT(fewer.base_vertices, more.base_vertices);
  const bool noted = std::any_of(fewer.notes.begin(), fewer.notes.end(), [](const std::string& note) {
    return note.find("levels still folded") != std::string::npos;
  });
  EXPECT_TRUE(noted);
}

TEST(Remesh, BunnyNpmClosedGenusZero) { CheckSharedMesh("bunny_npm.obj", 2, 0.9, 0.018); }
TEST(Remesh, RockerArmClosedGenusOne) { CheckSharedMesh("rocker-arm.off", 0, 0.9, 0.002); }

}  // namespace
}  // namespace eqmesh

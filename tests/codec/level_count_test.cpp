// Level-count search (coding/level_count_search.h): truncation is exact, the
// chosen stream meets the rate and is never worse than coding every level.
#include <gtest/gtest.h>

#include "codec_fixtures.h"
#include "coding/decoder.h"
#include "coding/level_count_search.h"
#include "metrics/surface_distance.h"

namespace eqmesh {
namespace {

using testing::MakeBumpySphere;

Mesh Finest(const SemiRegularMesh& m) { return ExtractLevel(m, m.hierarchy.levels()); }

TEST(LevelCount, TruncationKeepsTheCoarseLevelsExactly) {
  const SemiRegularMesh full = MakeBumpySphere(4);
  auto cut = TruncateLevels(full, 2);
  ASSERT_TRUE(cut.ok()) << cut.status().message();
  EXPECT_EQ(cut->hierarchy.levels(), 2);
  ASSERT_EQ(cut->positions.size(), full.hierarchy.NumVertices(2));
  for (size_t v = 0; v < cut->positions.size(); ++v) EXPECT_EQ(cut->positions[v], full.positions[v]);
  EXPECT_EQ(cut->hierarchy.Faces(2), full.hierarchy.Faces(2));
  EXPECT_FALSE(TruncateLevels(full, 5).ok());
  EXPECT_FALSE(TruncateLevels(full, -1).ok());
}

TEST(LevelCount, ChosenStreamMeetsTheRateAndBeatsAllLevels) {
  const SemiRegularMesh mesh = MakeBumpySphere(4);
  const Mesh original = Finest(mesh);
  EncodeOptions options;
  options.input_vertices = original.positions.size();
  options.original = &original;
  options.target_bpv = 2.0;
  EncodeReport report;
  LevelCountReport levels;
  auto bytes = EncodeChoosingLevels(mesh, options, &report, &levels);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  ASSERT_FALSE(levels.trials.empty());
  EXPECT_GE(levels.chosen_levels, 1);
  EXPECT_LE(levels.chosen_levels, mesh.hierarchy.levels());
  EXPECT_LE(report.bpv, 2.0 * 1.03);
  auto decoded = Decode(bytes->data(), bytes->size());
  ASSERT_TRUE(decoded.ok());
  for (const LevelCountTrial& t : levels.trials) {
    EXPECT_GE(report.psnr_db + 1e-9, t.psnr_db) << "level count " << t.levels << " was better";
  }
}

TEST(LevelCount, WithoutTargetEveryLevelIsCoded) {
  const SemiRegularMesh mesh = MakeBumpySphere(3);
  EncodeOptions options;
  LevelCountReport levels;
  auto bytes = EncodeChoosingLevels(mesh, options, nullptr, &levels);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_EQ(levels.chosen_levels, 3);
  EXPECT_TRUE(levels.trials.empty());
}

// A 50 dB target against `original` at 50k samples: the search's logic, not the
// meter's precision, is under test.
EncodeOptions Psnr50Against(const Mesh& original) {
  EncodeOptions options;
  options.input_vertices = original.positions.size();
  options.original = &original;
  options.target_psnr = 50.0;
  options.psnr_samples = 50'000;
  return options;
}

TEST(LevelCount, PsnrTargetGivesTheSmallestStreamThatMeetsIt) {
  const SemiRegularMesh mesh = MakeBumpySphere(4);
  const Mesh original = Finest(mesh);
  const EncodeOptions options = Psnr50Against(original);
  EncodeReport report;
  LevelCountReport levels;
  auto bytes = EncodeChoosingLevels(mesh, options, &report, &levels);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_GE(report.psnr_db, 50.0);
  // A level count whose uncoded truncation already misses the target is
  // measured, not searched: it reports that ceiling and no stream was made.
  size_t skipped = 0;
  for (const LevelCountTrial& t : levels.trials) {
    if (t.feasible) {
      EXPECT_LE(bytes->size(), t.bytes);
    }
    if (t.coded) continue;
    ++skipped;
    EXPECT_FALSE(t.feasible) << t.levels;
    EXPECT_LT(t.psnr_db, options.target_psnr) << t.levels;
    EXPECT_EQ(t.bytes, 0u) << t.levels;
  }
  EXPECT_GE(skipped, 1u) << "this mesh's coarsest level cannot reach 50 dB";
  ASSERT_FALSE(levels.trials.empty());
  EXPECT_TRUE(levels.trials.back().coded);
}

// A bound (EncodeOptions::outbid_bytes) changes nothing for a search whose
// answer is smaller than it, and gives the search up (kOutbid, no stream) once
// a pass misses the target in at least that many bytes: here every pass that
// misses does, against a bound of one byte.
TEST(LevelCount, APsnrSearchGivesUpOnlyWhereItCannotBeatItsBound) {
  const SemiRegularMesh mesh = MakeBumpySphere(4);
  const Mesh original = Finest(mesh);
  EncodeOptions options = Psnr50Against(original);
  auto free = EncodeChoosingLevels(mesh, options, nullptr, nullptr);
  ASSERT_TRUE(free.ok()) << free.status().message();
  options.outbid_bytes = free->size() + 1;
  auto bounded = EncodeChoosingLevels(mesh, options, nullptr, nullptr);
  ASSERT_TRUE(bounded.ok()) << bounded.status().message();
  EXPECT_EQ(*bounded, *free);
  options.outbid_bytes = 1;
  auto outbid = EncodeChoosingLevels(mesh, options, nullptr, nullptr);
  ASSERT_FALSE(outbid.ok());
  EXPECT_EQ(outbid.status().code(), StatusCode::kOutbid) << outbid.status().message();
}

}  // namespace
}  // namespace eqmesh

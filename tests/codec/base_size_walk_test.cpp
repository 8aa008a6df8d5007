// Base-size walk (coding/base_size_walk.h): with a target, remeshes at other base
// sizes replace the remesher's only where they do better at that target; the
// stream returned meets the target on the decoded mesh and is reproducible; the
// walk stays out of untargeted encodes, dense inputs and fixed remesh shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "coding/base_size_walk.h"
#include "coding/decoder.h"
#include "coding/representation_choice.h"
#include "metrics/surface_distance.h"
#include "remesh/remesh.h"
#include "test_support.h"

namespace eqmesh {
namespace {

// A sphere with long, narrow ridges around it: the remesher's error bound keeps
// a small base, while the ridges' details fill the levels.
Mesh RidgedSphere() {
  Mesh m = testing::MakeIcosphere(3);
  for (Vec3& p : m.positions) {
    const double ridge = std::pow(std::sin(9.0 * std::atan2(p.y(), p.x())), 8.0);
    p *= 1.0 + 0.12 * ridge * (1.0 - p.z() * p.z());
  }
  return m;
}

// A target against `original` at 20k samples (the walk, not the meter's
// precision, is under test): `psnr` dB, or with psnr 0 none.
EncodeOptions TargetAgainst(const Mesh& original, double psnr = 0) {
  EncodeOptions options;
  options.original = &original;
  options.input_vertices = original.positions.size();
  options.psnr_samples = 20'000;
  options.target_psnr = psnr;
  return options;
}

BaseSizeTry FirstTry(const Mesh& input, const RemeshOptions& remesh, const EncodeOptions& options) {
  RemeshReport report;
  auto mesh = Remesh(input, remesh, &report);
  EXPECT_TRUE(mesh.ok()) << mesh.status().ToString();
  BaseSizeTry first;
  if (!mesh.ok()) return first;
  first.base_vertices = mesh->hierarchy.NumVertices(0);
  first.stream = EncodeChoosingLevels(*mesh, options, &first.report, &first.levels);
  return first;
}

double DecodedPsnr(const Mesh& original, const std::vector<uint8_t>& stream) {
  auto decoded = Decode(stream.data(), stream.size());
  EXPECT_TRUE(decoded.ok());
  if (!decoded.ok()) return 0.0;
  CompareOptions compare;
  compare.samples = 20'000;
  auto distance = CompareSurfaces(original, *decoded, compare);
  EXPECT_TRUE(distance.ok());
  return distance.ok() ? distance->psnr_db : 0.0;
}

TEST(BaseSizeWalk, NeverLargerThanTheRemeshersBaseAndMeetsThePsnrTarget) {
  const Mesh input = RidgedSphere();
  const EncodeOptions options = TargetAgainst(input, 42.0);
  const RemeshOptions remesh;
  BaseSizeTry first = FirstTry(input, remesh, options);
  ASSERT_TRUE(first.stream.ok()) << first.stream.status().ToString();
  const size_t first_bytes = first.stream->size();
  const size_t first_base = first.base_vertices;
  std::vector<size_t> tried;
  const BaseSizeTry best = WalkBaseSizes(input, remesh, options, std::move(first), &tried);
  ASSERT_TRUE(best.stream.ok());
  ASSERT_FALSE(tried.empty());
  EXPECT_EQ(tried.front(), 2 * first_base);  // the first try doubles the base
  EXPECT_LE(best.stream->size(), first_bytes);
  EXPECT_EQ(best.stream->size(), best.report.total_bytes);
  EXPECT_GE(DecodedPsnr(input, *best.stream), options.target_psnr);
  if (best.base_vertices != first_base) {
    EXPECT_LT(best.stream->size(), first_bytes);  // replaced only by a smaller stream
    EXPECT_EQ(best.remesh.base_vertices, best.base_vertices);
  }
}

TEST(BaseSizeWalk, IsDeterministic) {
  const Mesh input = RidgedSphere();
  const EncodeOptions options = TargetAgainst(input, 42.0);
  const RemeshOptions remesh;
  const BaseSizeTry a = WalkBaseSizes(input, remesh, options, FirstTry(input, remesh, options));
  const BaseSizeTry b = WalkBaseSizes(input, remesh, options, FirstTry(input, remesh, options));
  ASSERT_TRUE(a.stream.ok());
  ASSERT_TRUE(b.stream.ok());
  EXPECT_EQ(*a.stream, *b.stream);
  EXPECT_EQ(a.base_vertices, b.base_vertices);
}

TEST(BaseSizeWalk, ARateTargetKeepsTheHigherPsnr) {
  const Mesh input = RidgedSphere();
  EncodeOptions options = TargetAgainst(input);
  options.target_bpv = 2.0;
  const RemeshOptions remesh;
  BaseSizeTry first = FirstTry(input, remesh, options);
  ASSERT_TRUE(first.stream.ok()) << first.stream.status().ToString();
  const double first_psnr = first.report.psnr_db;
  const BaseSizeTry best = WalkBaseSizes(input, remesh, options, std::move(first));
  ASSERT_TRUE(best.stream.ok());
  EXPECT_GE(best.report.psnr_db, first_psnr);
}

TEST(BaseSizeWalk, ATryReplacesOnlyWhatItBeatsAtTheTarget) {
  EncodeOptions psnr;
  psnr.target_psnr = 60.0;
  EncodeOptions rate;
  rate.target_bpv = 1.0;
  BaseSizeTry small, large, failed;
  small.stream = std::vector<uint8_t>(10);
  small.report.total_bytes = 10;
  small.report.psnr_db = 61.0;
  large.stream = std::vector<uint8_t>(20);
  large.report.total_bytes = 20;
  large.report.psnr_db = 65.0;
  failed.stream = Status(StatusCode::kTargetOutOfReach, "out of reach");
  EXPECT_TRUE(BeatsAtTarget(psnr, small, large));
  EXPECT_FALSE(BeatsAtTarget(psnr, large, small));
  EXPECT_TRUE(BeatsAtTarget(rate, large, small));
  EXPECT_FALSE(BeatsAtTarget(rate, small, large));
  EXPECT_FALSE(BeatsAtTarget(psnr, failed, small));
  EXPECT_TRUE(BeatsAtTarget(psnr, small, failed));
  EXPECT_FALSE(BeatsAtTarget(psnr, small, small));  // a tie keeps the first
}

TEST(BaseSizeWalk, ATryAtAPsnrTargetStartsAtTheBestsLambdaAndIsBoundByItsBytes) {
  const StatusOr<std::vector<uint8_t>> best = std::vector<uint8_t>(1234);
  EncodeReport best_report;
  best_report.lambda = 0.25;
  EncodeOptions psnr;
  psnr.target_psnr = 60.0;
  const EncodeOptions bounded = ToBeat(psnr, best, best_report);
  EXPECT_EQ(bounded.outbid_bytes, 1234u);
  EXPECT_EQ(bounded.lambda, 0.25);
  EncodeOptions rate;
  rate.target_bpv = 1.0;
  const EncodeOptions as_asked = ToBeat(rate, best, best_report);
  EXPECT_EQ(as_asked.outbid_bytes, 0u);
  EXPECT_EQ(as_asked.lambda, rate.lambda);
  const StatusOr<std::vector<uint8_t>> none = Status(StatusCode::kTargetOutOfReach, "out of reach");
  const EncodeOptions unbounded = ToBeat(psnr, none, best_report);  // nothing to beat yet
  EXPECT_EQ(unbounded.outbid_bytes, 0u);
  EXPECT_EQ(unbounded.lambda, psnr.lambda);
}

TEST(BaseSizeWalk, RunsOnlyWithATargetOnAMidSizeInput) {
  const Mesh input = RidgedSphere();
  EncodeOptions options = TargetAgainst(input);
  EXPECT_FALSE(BaseWalkApplies(options));  // a bare lambda
  options.target_psnr = 50.0;
  EXPECT_TRUE(BaseWalkApplies(options));
  options.original = nullptr;
  EXPECT_FALSE(BaseWalkApplies(options));
  Mesh dense;
  dense.positions.resize(kBaseWalkMaxInputVertices + 1, Vec3::Zero());
  options.original = &dense;
  EXPECT_FALSE(BaseWalkApplies(options));
}

TEST(BaseSizeWalk, TheRepresentationChoiceWalksOnlyWhereItMayChooseTheRemesh) {
  const Mesh input = RidgedSphere();
  const EncodeOptions options = TargetAgainst(input, 42.0);
  const RemeshOptions remesh;
  RemeshReport report;
  auto remeshed = Remesh(input, remesh, &report);
  ASSERT_TRUE(remeshed.ok());
  RepresentationOptions fixed;  // the caller fixed the remesh (a .srm, --levels, an atlas)
  RepresentationReport kept;
  auto stream = EncodeChoosingRepresentation(*remeshed, options, fixed, nullptr, nullptr, &kept);
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  EXPECT_TRUE(kept.base_sizes_tried.empty());
  EXPECT_EQ(kept.remeshed_base_vertices, remeshed->hierarchy.NumVertices(0));
  EXPECT_FALSE(kept.walked_remesh.has_value());

  RepresentationOptions open;
  open.remesh = &remesh;
  RepresentationReport walked;
  auto best = EncodeChoosingRepresentation(*remeshed, options, open, nullptr, nullptr, &walked);
  ASSERT_TRUE(best.ok()) << best.status().ToString();
  EXPECT_FALSE(walked.base_sizes_tried.empty());
  EXPECT_LE(best->size(), stream->size());
  EXPECT_EQ(walked.walked_remesh.has_value(), walked.remeshed_base_vertices != kept.remeshed_base_vertices);
}

}  // namespace
}  // namespace eqmesh

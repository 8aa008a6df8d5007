#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "metrics/area_sampler.h"
#include "metrics/sample_rng.h"
#include "metrics/surface_distance.h"
#include "test_support.h"

namespace eqmesh {
namespace {

Mesh Scaled(Mesh m, double s) {
  for (Vec3& p : m.positions) p *= s;
  return m;
}

Mesh Translated(Mesh m, const Vec3& t) {
  for (Vec3& p : m.positions) p += t;
  return m;
}

bool BitIdentical(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

void ExpectBitIdentical(const SurfaceDistance& x, const SurfaceDistance& y) {
  EXPECT_TRUE(BitIdentical(x.rms_ab, y.rms_ab));
  EXPECT_TRUE(BitIdentical(x.rms_ba, y.rms_ba));
  EXPECT_TRUE(BitIdentical(x.mean_ab, y.mean_ab));
  EXPECT_TRUE(BitIdentical(x.mean_ba, y.mean_ba));
  EXPECT_TRUE(BitIdentical(x.hausdorff, y.hausdorff));
  EXPECT_TRUE(BitIdentical(x.psnr_db, y.psnr_db));
}

TEST(SampleRng, ReproducibleAndInUnitInterval) {
  SampleRng a(42), b(42);
  for (int i = 0; i < 1000; ++i) {
    const double x = a.NextDouble();
    EXPECT_EQ(x, b.NextDouble());
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
  // Pinned output: SplitMix64 from state 0 (Vigna's reference value).
  EXPECT_EQ(SampleRng(0).Next(), 0xe220a8397b1dcdafULL);
  EXPECT_NE(SampleRng::ForBlock(1, 0, 0).Next(), SampleRng::ForBlock(1, 0, 1).Next());
  EXPECT_NE(SampleRng::ForBlock(1, 0, 0).Next(), SampleRng::ForBlock(1, 1, 0).Next());
}

TEST(AreaSampler, SamplesLieOnTheSurfaceProportionallyToArea) {
  // Two triangles, areas 1 and 3: stratification gives exactly 1/4 and 3/4.
  Mesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {10, 0, 0}, {13, 0, 0}, {10, 2, 0}};
  m.faces = {{0, 1, 2}, {3, 4, 5}, {0, 0, 1}};  // plus a degenerate face, never sampled
  auto s = AreaSampler::Build(m);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_DOUBLE_EQ(s->total_area(), 4.0);
  SampleRng rng(1);
  std::vector<Vec3> pts;
  s->Sample(4000, 0, 4000, &rng, &pts);
  ASSERT_EQ(pts.size(), 4000u);
  int first = 0;
  for (const Vec3& p : pts) {
    EXPECT_EQ(p.z(), 0.0);
    if (p.x() < 5) {
      ++first;
      EXPECT_LE(p.x() / 2 + p.y(), 1.0 + 1e-12);
    } else {
      EXPECT_LE((p.x() - 10) / 3 + p.y() / 2, 1.0 + 1e-12);
    }
  }
  EXPECT_EQ(first, 1000);
}

TEST(CompareSurfaces, MeshAgainstItselfIsExactlyZero) {
  const Mesh m = testing::MakeTorus(32, 16);
  auto d = CompareSurfaces(m, m, {20000, 1, 2});
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->rms, 0.0);
  EXPECT_EQ(d->mean, 0.0);
  EXPECT_EQ(d->hausdorff, 0.0);
  EXPECT_TRUE(std::isinf(d->psnr_db) && d->psnr_db > 0);
  EXPECT_EQ(d->samples, 20000u);
}

TEST(CompareSurfaces, SphereOfRadiusOnePlusDHasRmsNearD) {
  const double dr = 0.01;
  const Mesh inner = testing::MakeIcosphere(6);
  const Mesh outer = Scaled(inner, 1.0 + dr);
  auto d = CompareSurfaces(inner, outer, {50000, 7, 2});
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  // The tessellations are similar, so every point is ~dr from the other surface.
  EXPECT_NEAR(d->rms, dr, 0.02 * dr);
  EXPECT_NEAR(d->rms_ab, dr, 0.02 * dr);
  EXPECT_NEAR(d->rms_ba, dr, 0.02 * dr);
  EXPECT_NEAR(d->mean, dr, 0.02 * dr);
  EXPECT_NEAR(d->hausdorff, dr, 0.05 * dr);
  EXPECT_NEAR(d->bbox_diagonal, 2.0 * std::sqrt(3.0), 0.01);
  EXPECT_NEAR(d->psnr_db, PsnrDb(d->bbox_diagonal, d->rms), 1e-12);
}

TEST(CompareSurfaces, TranslatedCopyIsBoundedByTheTranslation) {
  const Mesh a = testing::MakeTorus(40, 20);
  const Vec3 t(0.03, -0.02, 0.01);
  const Mesh b = Translated(a, t);
  auto d = CompareSurfaces(a, b, {50000, 3, 2});
  ASSERT_TRUE(d.ok());
  EXPECT_GT(d->hausdorff, 0.0);
  EXPECT_LE(d->hausdorff, t.norm() * (1 + 1e-12));
  EXPECT_GT(d->rms, 0.0);
  EXPECT_LE(d->rms, d->hausdorff);
  EXPECT_LE(d->mean, d->rms);
}

TEST(PsnrDb, HandComputedValues) {
  EXPECT_DOUBLE_EQ(PsnrDb(1.0, 0.01), 40.0);  // 20 log10(100)
  EXPECT_DOUBLE_EQ(PsnrDb(2.0, 0.002), 60.0);
  EXPECT_NEAR(PsnrDb(3.0, 1.0), 9.5424250943932, 1e-12);
  EXPECT_TRUE(std::isinf(PsnrDb(1.0, 0.0)));
}

TEST(CompareSurfaces, DeterministicAcrossThreadCountsAndRuns) {
  const Mesh a = testing::MakeIcosphere(4);
  Mesh b = testing::MakeIcosphere(3);
  for (size_t i = 0; i < b.positions.size(); ++i) b.positions[i] *= 1.0 + 0.003 * std::sin(7.0 * static_cast<double>(i));
  // 3 x 4096 + 5 samples: several blocks and a partial last one.
  CompareOptions options{3 * 4096 + 5, 99, 1};
  auto one = CompareSurfaces(a, b, options);
  options.threads = 2;
  auto two = CompareSurfaces(a, b, options);
  options.threads = 5;
  auto five = CompareSurfaces(a, b, options);
  auto again = CompareSurfaces(a, b, options);
  ASSERT_TRUE(one.ok() && two.ok() && five.ok() && again.ok());
  EXPECT_GT(one->rms, 0.0);
  ExpectBitIdentical(*one, *two);
  ExpectBitIdentical(*one, *five);
  ExpectBitIdentical(*five, *again);
  // A different seed gives a different (but close) estimate.
  options.seed = 100;
  auto other_seed = CompareSurfaces(a, b, options);
  ASSERT_TRUE(other_seed.ok());
  EXPECT_NE(other_seed->rms_ab, one->rms_ab);
  EXPECT_NEAR(other_seed->rms, one->rms, 0.05 * one->rms);
}

TEST(CompareSurfaces, DefaultSampleCountIsUsedWhenZero) {
  const Mesh m = testing::MakeIcosphere(1);
  EXPECT_EQ(DefaultSampleCount(m), 1'000'000u);
  // Ten per vertex of the original alone (163,842 vertices): an approximation's
  // vertex count does not enter.
  EXPECT_EQ(DefaultSampleCount(testing::MakeIcosphere(7)), 1'638'420u);
}

TEST(CompareSurfaces, RejectsBadInputWithClearErrors) {
  const Mesh good = testing::MakeIcosphere(1);
  Mesh empty;
  auto r = CompareSurfaces(empty, good);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("no vertices"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("original"), std::string::npos);

  Mesh no_faces = good;
  no_faces.faces.clear();
  r = CompareSurfaces(good, no_faces);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("no faces"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("other"), std::string::npos);

  Mesh nan = good;
  nan.positions[5].x() = NAN;
  EXPECT_EQ(CompareSurfaces(good, nan).status().code(), StatusCode::kInvalidMesh);
  EXPECT_EQ(ValidateForCompare(nan).code(), StatusCode::kInvalidMesh);

  Mesh flat;
  flat.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat.faces = {{0, 1, 2}};
  r = CompareSurfaces(flat, good);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("zero area"), std::string::npos) << r.status().message();

  Mesh bad_index = good;
  bad_index.faces[0][2] = 1000;
  EXPECT_EQ(CompareSurfaces(good, bad_index).status().code(), StatusCode::kInvalidMesh);

  EXPECT_EQ(CompareSurfaces(good, good, {kMaxCompareSamples + 1, 1, 1}).status().code(),
            StatusCode::kResourceLimit);
  EXPECT_EQ(CompareSurfaces(good, good, {100, 1, -1}).status().code(), StatusCode::kInvalidArgument);
}

// A series keeps the last measured mesh's tree and what each sample found, to
// refit and start from for the next mesh with the same faces: every measurement
// of a series gives the doubles a fresh comparison gives, through meshes with
// the same faces (moved), other faces, other sample counts and seeds, and
// another original.
TEST(ReferenceSurface, MeasuresASeriesAsSeparateComparisons) {
  const Mesh a = testing::MakeTorus(30, 14);
  const Mesh a2 = testing::MakeTorus(20, 10);
  auto reference = ReferenceSurface::Build(a);
  auto reference2 = ReferenceSurface::Build(a2);
  ASSERT_TRUE(reference.ok() && reference2.ok());
  const Mesh coarse = testing::MakeTorus(24, 12);
  const Mesh fine = testing::MakeTorus(36, 16);
  ApproximationSeries series;
  int step = 0;
  for (const Mesh* shape : {&coarse, &coarse, &fine, &fine, &coarse}) {
    for (const CompareOptions& options : {CompareOptions{3 * 4096 + 5, 11, 2}, CompareOptions{5000, 12, 1}}) {
      Mesh other = Translated(*shape, Vec3(0.001 * step, -0.002 * step, 0.0));
      other.positions[3] += Vec3(0.0, 0.0, 0.01 * (step % 3));
      ++step;
      for (const ReferenceSurface* ref : {&*reference, &*reference2}) {
        auto expected = ref->Compare(other, options);
        auto got = ref->Compare(other, options, &series);
        ASSERT_TRUE(expected.ok() && got.ok()) << step;
        ExpectBitIdentical(*expected, *got);
      }
    }
  }
  Mesh broken = coarse;
  broken.faces[0][1] = 100000;
  EXPECT_FALSE(reference->Compare(broken, {}, &series).ok());
  auto after = reference->Compare(coarse, CompareOptions{4096, 3, 1}, &series);
  auto fresh = reference->Compare(coarse, CompareOptions{4096, 3, 1});
  ASSERT_TRUE(after.ok() && fresh.ok());
  ExpectBitIdentical(*fresh, *after);
}

}  // namespace
}  // namespace eqmesh

namespace eqmesh {
namespace {

// Squared lengths of a 1e300 or 1e-300 mesh over- or underflow; the meter works
// at unit scale (a power of two, exact) and reports lengths in the input's units.
TEST(CompareSurfaces, ExtremeScalesMeasureAsAtUnitScale) {
  const Mesh a = testing::MakeIcosphere(3);
  const Mesh b = testing::MakeIcosphere(3, 1.01);
  CompareOptions options;
  options.samples = 20'000;
  auto unit = CompareSurfaces(a, b, options);
  ASSERT_TRUE(unit.ok()) << unit.status().ToString();
  for (const double scale : {0x1p900, 0x1p-900}) {
    auto scaled = CompareSurfaces(Scaled(a, scale), Scaled(b, scale), options);
    ASSERT_TRUE(scaled.ok()) << scale << ": " << scaled.status().ToString();
    EXPECT_EQ(scaled->psnr_db, unit->psnr_db) << scale;
    EXPECT_EQ(scaled->rms, unit->rms * scale) << scale;
    EXPECT_EQ(scaled->hausdorff, unit->hausdorff * scale) << scale;
    EXPECT_TRUE(ValidateForCompare(Scaled(a, scale)).ok()) << scale;
  }
  // Not a power of two: the same to rounding.
  auto huge = CompareSurfaces(Scaled(a, 1e300), Scaled(b, 1e300), options);
  ASSERT_TRUE(huge.ok()) << huge.status().ToString();
  EXPECT_NEAR(huge->psnr_db, unit->psnr_db, 1e-6);
}

// The encoder measures every trial stream against one original, prepared once:
// each comparison must give CompareSurfaces' doubles, at ordinary and extreme
// scales, and errors on the other mesh as CompareSurfaces gives them.
TEST(ReferenceSurface, ComparesEachMeshAsCompareSurfacesDoes) {
  const Mesh a = testing::MakeTorus(30, 14);
  for (const double scale : {1.0, 0x1p900}) {
    const Mesh original = Scaled(a, scale);
    auto reference = ReferenceSurface::Build(original);
    ASSERT_TRUE(reference.ok()) << reference.status().ToString();
    for (const Vec3& t : {Vec3(0.01, 0.0, 0.0), Vec3(0.0, -0.02, 0.005)}) {
      const Mesh other = Scaled(Translated(testing::MakeTorus(24, 12), t), scale);
      const CompareOptions options{3 * 4096 + 5, 11, 2};
      auto expected = CompareSurfaces(original, other, options);
      auto got = reference->Compare(other, options);
      ASSERT_TRUE(expected.ok() && got.ok());
      EXPECT_GT(got->rms, 0.0);
      ExpectBitIdentical(*expected, *got);
    }
  }
  Mesh broken = testing::MakeIcosphere(1);
  broken.faces[0][1] = 100000;
  auto reference = ReferenceSurface::Build(a);
  ASSERT_TRUE(reference.ok());
  const auto status = reference->Compare(broken).status();
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(status.ToString(), CompareSurfaces(a, broken).status().ToString());
  EXPECT_FALSE(ReferenceSurface::Build(Mesh()).ok());
}

}  // namespace
}  // namespace eqmesh

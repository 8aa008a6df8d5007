#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "coding/eq/eq_decoder.h"
#include "coding/eq/eq_encoder.h"
#include "coding/eq/eq_layout.h"
#include "coding/eq/eq_model.h"
#include "core/thread_count.h"
#include "test_support.h"

namespace eqmesh {
namespace {

SemiRegularHierarchy IcoHierarchy(int levels) {
  const Mesh ico = testing::MakeIcosphere(0);
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(ico.num_vertices()), ico.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  return std::move(h).value();
}

// Positions of every hierarchy vertex on the unit sphere (midpoints pushed out).
std::vector<Vec3> SpherePositions(const SemiRegularHierarchy& h) {
  std::vector<Vec3> p = testing::MakeIcosphere(0).positions;
  for (int j = 0; j < h.levels(); ++j) {
    for (uint32_t k = 0; k < h.NumOddVertices(j); ++k) {
      const Edge& e = h.OddEdge(j, k);
      p.push_back((p[e[0]] + p[e[1]]).normalized());
    }
  }
  return p;
}

// Synthetic wavelet coefficients of level j: Laplacian noise whose sigma varies
// smoothly over the sphere (large near +z, tiny near -z) and halves per level;
// tangential components 10x smaller.
std::vector<Vec3> SyntheticCoefficients(const SemiRegularHierarchy& h, int j, uint32_t seed) {
  const std::vector<Vec3> p = SpherePositions(h);
  std::mt19937 rng(seed);
  std::exponential_distribution<double> expo(1.0);
  auto laplace = [&]() { return (rng() & 1 ? 1.0 : -1.0) * expo(rng) / std::sqrt(2.0); };
  std::vector<Vec3> c(h.NumOddVertices(j));
  for (uint32_t k = 0; k < c.size(); ++k) {
    const Vec3& x = p[h.NumVertices(j) + k];
    const double sigma = std::ldexp(0.02, -j) * std::exp(2.5 * x.z() + std::sin(4 * x.x()));
    c[k] = Vec3(sigma * laplace(), 0.1 * sigma * laplace(), 0.1 * sigma * laplace());
  }
  return c;
}

constexpr double kQ0 = 1.0 / (1 << 24);

double Mse(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double s = 0;
  for (size_t k = 0; k < a.size(); ++k) s += (a[k] - b[k]).squaredNorm();
  return s / static_cast<double>(a.size());
}

TEST(EqLayout, ScanIsPermutationWithCausalNeighbourhoods) {
  const SemiRegularHierarchy h = IcoHierarchy(4);
  for (int j = 0; j < 4; ++j) {
    auto layout = BuildEqLevelLayout(h, j);
    ASSERT_TRUE(layout.ok()) << layout.status().ToString();
    const EqLevelLayout& l = *layout;
    ASSERT_EQ(l.size(), h.NumOddVertices(j));
    std::set<uint32_t> seen(l.scan.begin(), l.scan.end());
    EXPECT_EQ(seen.size(), l.size());
    // Ring-1 neighbours are edges of the level j+1 mesh.
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const Face& f : h.Faces(j + 1))
      for (int a = 0; a < 3; ++a) edges.insert({f[a], f[(a + 1) % 3]});
    size_t with_neighbours = 0;
    for (uint32_t i = 0; i < l.size(); ++i) {
      bool any = false;
      for (uint32_t e = l.offsets[i]; e < l.offsets[i + 1]; ++e) {
        ASSERT_LT(l.neighbours[e], i);
        ASSERT_GE(l.ring[e], 1);
        ASSERT_LE(l.ring[e], 3);
        any = true;
        if (l.ring[e] == 1) {
          const uint32_t a = l.first_vertex + l.scan[i], b = l.first_vertex + l.scan[l.neighbours[e]];
          EXPECT_TRUE(edges.count({a, b}) || edges.count({b, a}));
        }
      }
      with_neighbours += any;
    }
    // Only the first vertex of a triangle can lack one (its neighbours across a
    // shared edge may lie beyond three rings), never more than one per triangle.
    EXPECT_GE(with_neighbours + h.BaseFaces().size(), l.size());
    if (j >= 2) {
      EXPECT_GT(static_cast<double>(with_neighbours), 0.99 * static_cast<double>(l.size()));
    }
    if (j >= 2) {
      // Interior vertices see a good part of their (up to ~30) three-ring neighbours.
      const double mean = static_cast<double>(l.neighbours.size()) / static_cast<double>(l.size());
      EXPECT_GT(mean, 8.0);
    }
  }
}

TEST(EqLayout, BaseTrianglesAreScannedInOrderAndBoundaryMeshesWork) {
  const Mesh disc = testing::MakeDisc(2);
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(disc.num_vertices()), disc.faces, 3);
  ASSERT_TRUE(h.ok());
  for (int j = 0; j < 3; ++j) {
    auto layout = BuildEqLevelLayout(*h, j);
    ASSERT_TRUE(layout.ok()) << layout.status().ToString();
    EXPECT_EQ(layout->size(), h->NumOddVertices(j));
  }
  EXPECT_FALSE(BuildEqLevelLayout(*h, 3).ok());
  EXPECT_FALSE(BuildEqLevelLayout(*h, -1).ok());
}

TEST(EqModel, IntegerLogIsExact) {
  EXPECT_EQ(Log2Sixteenths(1), 0);
  EXPECT_EQ(Log2Sixteenths(2), 16);
  EXPECT_EQ(Log2Sixteenths(3), 25);  // 16 log2 3 = 25.36
  EXPECT_EQ(Log2Sixteenths(1ull << 40), 640);
  EXPECT_EQ(Log2Sixteenths((1ull << 40) - 1), 639);
  EXPECT_EQ(Log2Sixteenths(static_cast<EqUint128>(1) << 100), 1600);
  for (uint64_t x = 1; x < 5000; ++x) {
    EXPECT_EQ(Log2Sixteenths(x), static_cast<int32_t>(std::floor(16 * std::log2(static_cast<double>(x)) + 1e-12)))
        << x;
  }
}

struct Coded {
  std::vector<uint8_t> bytes;
  std::vector<Vec3> recon;
  EqEncodeStats stats;
};

// tangential_context false writes the chunks of streams 1.0-1.2 (iid tangential).
Coded EncodeOrDie(const EqLevelLayout& layout, const std::vector<Vec3>& c, int32_t lambda_code,
                  bool tangential_context = true) {
  EqEncodeOptions opt;
  opt.lambda_code = lambda_code;
  opt.tangential_context = tangential_context;
  Coded out;
  auto bytes = EncodeEqLevel(layout, c, kQ0, opt, &out.recon, &out.stats);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  out.bytes = std::move(bytes).value();
  return out;
}

// lambda code for "distortion weighted so that the step is about `step` world units".
int32_t LambdaForStep(double step) { return EqLambdaCode(8.66 / (step * step), kQ0); }

StatusOr<std::vector<Vec3>> Decode(const EqLevelLayout& layout, const uint8_t* data, size_t size,
                                   bool tangential_context = true) {
  return DecodeEqLevel(layout, data, size, kQ0, tangential_context);
}

TEST(EqCoder, RoundTripIsExactAndDeterministic) {
  const SemiRegularHierarchy h = IcoHierarchy(4);
  for (int j : {0, 2, 3}) {
    auto layout = BuildEqLevelLayout(h, j);
    ASSERT_TRUE(layout.ok());
    const std::vector<Vec3> c = SyntheticCoefficients(h, j, 11u + static_cast<uint32_t>(j));
    for (double step : {1e-2, 1e-3, 1e-4, 1e-5}) {
     for (bool context : {true, false}) {
      const Coded a = EncodeOrDie(*layout, c, LambdaForStep(step), context);
      const Coded b = EncodeOrDie(*layout, c, LambdaForStep(step), context);
      EXPECT_EQ(a.bytes, b.bytes);
      auto decoded = Decode(*layout, a.bytes.data(), a.bytes.size(), context);
      ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
      ASSERT_EQ(decoded->size(), c.size());
      for (size_t k = 0; k < c.size(); ++k) {
        ASSERT_EQ((*decoded)[k], a.recon[k]) << "level " << j << " step " << step << " vertex " << k;
      }
     }
    }
  }
}

// A level large enough for its two streams to iterate on two threads codes the
// same bytes, reconstruction and side information as on one, and decodes exactly.
TEST(EqCoder, TwoThreadsCodeWhatOneCodes) {
  const SemiRegularHierarchy h = IcoHierarchy(5);
  auto layout = BuildEqLevelLayout(h, 4);
  ASSERT_TRUE(layout.ok());
  ASSERT_GE(layout->size(), 4096u);  // the encoder's side-by-side threshold
  const std::vector<Vec3> c = SyntheticCoefficients(h, 4, 23);
  for (double step : {1e-3, 1e-5}) {
    SetWorkerThreadLimit(1);
    const Coded one = EncodeOrDie(*layout, c, LambdaForStep(step));
    SetWorkerThreadLimit(2);
    const Coded two = EncodeOrDie(*layout, c, LambdaForStep(step));
    SetWorkerThreadLimit(0);
    EXPECT_EQ(one.bytes, two.bytes);
    EXPECT_EQ(one.recon, two.recon);
    EXPECT_EQ(one.stats.iterations, two.stats.iterations);
    EXPECT_EQ(one.stats.unpredictable, two.stats.unpredictable);
    auto decoded = Decode(*layout, two.bytes.data(), two.bytes.size());
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    EXPECT_EQ(*decoded, two.recon);
  }
}

// Each reconstruction lies within (dead zone + 2 steps) sigma of the input for the
// quantizer the decoder itself selects (the R-D choice may move one bin down).
TEST(EqCoder, ReconstructionErrorWithinQuantizerBound) {
  const SemiRegularHierarchy h = IcoHierarchy(4);
  auto layout = BuildEqLevelLayout(h, 3);
  ASSERT_TRUE(layout.ok());
  const EqLevelLayout& l = *layout;
  const std::vector<Vec3> c = SyntheticCoefficients(h, 3, 5);
  for (double step : {1e-3, 1e-4, 1e-5}) {
    const Coded a = EncodeOrDie(l, c, LambdaForStep(step));
    // Both streams in scan order, as the decoder sees them: normal i, tangential 2i + c.
    std::vector<int64_t> recon_n(l.size()), recon_t(2 * l.size());
    for (size_t i = 0; i < l.size(); ++i) {
      recon_n[i] = std::llround(a.recon[l.scan[i]][0] / kQ0);
      recon_t[2 * i] = std::llround(a.recon[l.scan[i]][1] / kQ0);
      recon_t[2 * i + 1] = std::llround(a.recon[l.scan[i]][2] / kQ0);
    }
    const EqContextTerms normal_terms(l, false), tangential_terms(l, true);
    for (size_t i = 0; i < l.size(); ++i) {
      const uint32_t k = l.scan[i];
      for (int comp = 0; comp < 3; ++comp) {
        const EqChoice choice = comp == 0 ? ChooseQuantizer(a.stats.side, recon_n.data(), normal_terms, i)
                                          : ChooseQuantizer(a.stats.side, recon_t.data(), tangential_terms,
                                                            2 * i + static_cast<size_t>(comp - 1));
        const EqQuantizer& q = choice.quantizer;
        const double x = c[k][comp], r = a.recon[k][comp];
        if (q.codes_nothing()) {
          EXPECT_EQ(r, 0.0);
          continue;
        }
        const double sigma = static_cast<double>(q.sigma_q16) / 65536.0 * kQ0;
        const double bound = (q.entry->dead_zone_q16 + 2.0 * q.entry->step_q16) / 65536.0 * sigma + kQ0;
        EXPECT_LE(std::fabs(x - r), bound) << "vertex " << k << " component " << comp;
      }
    }
  }
}

// The tangential stream's terms: both components of every causal neighbour, with
// the normal stream's ring weights, and for the bitangent the vertex's own tangent.
TEST(EqModel, TangentialTermsAreNeighboursBothComponentsAndOwnTangent) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  const EqLevelLayout& l = *layout;
  const EqContextTerms normal_terms(l, false), tangential_terms(l, true);
  EXPECT_EQ(normal_terms.size(), l.size());
  EXPECT_EQ(tangential_terms.size(), 2 * l.size());
  for (size_t i = 0; i < l.size(); ++i) {
    std::vector<std::pair<size_t, uint32_t>> n, t0, t1;
    normal_terms.ForEach(i, [&](size_t v, uint32_t w) { n.push_back({v, w}); });
    tangential_terms.ForEach(2 * i, [&](size_t v, uint32_t w) { t0.push_back({v, w}); });
    tangential_terms.ForEach(2 * i + 1, [&](size_t v, uint32_t w) { t1.push_back({v, w}); });
    ASSERT_EQ(n.size(), l.offsets[i + 1] - l.offsets[i]);
    ASSERT_EQ(t0.size(), 2 * n.size());
    ASSERT_EQ(t1.size(), 2 * n.size() + 1);
    for (size_t e = 0; e < n.size(); ++e) {
      EXPECT_EQ(n[e].second, 4u >> (l.ring[l.offsets[i] + e] - 1));
      EXPECT_EQ(t0[2 * e], std::make_pair(2 * n[e].first, n[e].second));
      EXPECT_EQ(t0[2 * e + 1], std::make_pair(2 * n[e].first + 1, n[e].second));
      EXPECT_LT(t0[2 * e + 1].first, 2 * i);  // causal
    }
    EXPECT_EQ(t1.back(), std::make_pair(2 * i, 4u));
  }
}

// Tangential energy concentrated on a few clustered vertices (the non-normal ones
// of a real remesh) is what the 1.3 context model is for: it must code such a
// level in fewer bytes than the iid class of 1.0-1.2, at the same distortion or
// less, and both must round-trip.
TEST(EqCoder, TangentialContextCodesClusteredTangentialPartsSmaller) {
  const SemiRegularHierarchy h = IcoHierarchy(5);
  auto layout = BuildEqLevelLayout(h, 4);
  ASSERT_TRUE(layout.ok());
  std::vector<Vec3> c = SyntheticCoefficients(h, 4, 17);
  const std::vector<Vec3> p = SpherePositions(h);
  std::mt19937 rng(3);
  // Large enough to be coded at the options' tangential lambda (lambda / 100).
  std::normal_distribution<double> gauss(0.0, 5e-2);
  for (uint32_t k = 0; k < c.size(); ++k) {
    const bool cluster = p[h.NumVertices(4) + k].x() > 0.85;  // ~7 % of the sphere
    c[k][1] = cluster ? gauss(rng) : 0.0;
    c[k][2] = cluster ? gauss(rng) : 0.0;
  }
  // (At 1e-3 both code no tangential part: the unpredictable class, fitted over
  // mostly zeros, codes nothing, so no cluster gets a non-zero seed.) Measured:
  // 25 / 18 / 13 % fewer bytes at 0.69 / 1.01 / 1.02 times the squared error.
  for (double step : {3e-4, 1e-4, 3e-5}) {
    const Coded iid = EncodeOrDie(*layout, c, LambdaForStep(step), false);
    const Coded context = EncodeOrDie(*layout, c, LambdaForStep(step), true);
    EXPECT_LT(context.bytes.size(), iid.bytes.size()) << "step " << step;
    EXPECT_LE(Mse(context.recon, c), 1.05 * Mse(iid.recon, c)) << "step " << step;
    for (const auto& [coded, flag] : {std::make_pair(&iid, false), std::make_pair(&context, true)}) {
      auto d = Decode(*layout, coded->bytes.data(), coded->bytes.size(), flag);
      ASSERT_TRUE(d.ok()) << d.status().ToString();
      for (size_t k = 0; k < c.size(); ++k) ASSERT_EQ((*d)[k], coded->recon[k]);
    }
  }
}

TEST(EqCoder, RateFallsAndDistortionRisesAsLambdaFalls) {
  const SemiRegularHierarchy h = IcoHierarchy(5);
  auto layout = BuildEqLevelLayout(h, 4);
  ASSERT_TRUE(layout.ok());
  const std::vector<Vec3> c = SyntheticCoefficients(h, 4, 9);
  size_t prev_bytes = SIZE_MAX;
  double prev_mse = -1;
  for (int32_t code = LambdaForStep(1e-6); code >= LambdaForStep(1e-2); code -= 16) {
    const Coded a = EncodeOrDie(*layout, c, code);
    const double mse = Mse(a.recon, c);
    EXPECT_LE(a.bytes.size(), prev_bytes) << "lambda code " << code;
    EXPECT_GE(mse, prev_mse) << "lambda code " << code;
    prev_bytes = a.bytes.size();
    prev_mse = mse;
  }
}

TEST(EqCoder, UnpredictableSetConverges) {
  const SemiRegularHierarchy h = IcoHierarchy(5);
  for (int j : {2, 4}) {
    auto layout = BuildEqLevelLayout(h, j);
    ASSERT_TRUE(layout.ok());
    const std::vector<Vec3> c = SyntheticCoefficients(h, j, 21);
    for (double step : {1e-2, 1e-3, 1e-4}) {
      const Coded a = EncodeOrDie(*layout, c, LambdaForStep(step));
      // A fixed point, or a short cycle between two partitions (coded with the
      // cheaper of the side informations), within a few iterations.
      EXPECT_TRUE(a.stats.converged || a.stats.cycle_length > 0) << "level " << j << " step " << step;
      EXPECT_LE(a.stats.cycle_length, 2);
      EXPECT_LE(a.stats.iterations, 8);
      if (!a.stats.converged) {
        EXPECT_LT(a.stats.last_change, layout->size() / 20);
      }
      EXPECT_LT(a.stats.unpredictable, layout->size());
    }
  }
}

// Huge outliers among tiny coefficients force the longest escapes (suffixes over
// 32 bits); the chunk must still round-trip exactly, at every rate.
TEST(EqCoder, OutliersUseLongEscapesAndRoundTrip) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss(0.0, 4.0 * kQ0);
  std::vector<Vec3> c(layout->size());
  for (Vec3& v : c) v = Vec3(gauss(rng), gauss(rng), gauss(rng));
  const double big = static_cast<double>(kEqMaxCoefficient / 2 - 1) * kQ0;
  for (size_t k = 0; k < c.size(); k += 37) c[k] = Vec3(k % 2 ? big : -big, big / 3, -big / 5);
  for (int32_t code : {-400, -100, 0, 200, 600}) {
    const Coded a = EncodeOrDie(*layout, c, code);
    auto d = Decode(*layout, a.bytes.data(), a.bytes.size());
    ASSERT_TRUE(d.ok()) << d.status().ToString();
    for (size_t k = 0; k < c.size(); ++k) ASSERT_EQ((*d)[k], a.recon[k]) << code << " " << k;
    // At fine lambda the outliers themselves come back accurately.
    if (code >= 200) {
      EXPECT_NEAR(a.recon[0][0], c[0][0], 1e-3 * big);
    }
  }
}

TEST(EqCoder, ZeroAndTinyFieldsCostAlmostNothing) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  const std::vector<Vec3> zero(layout->size(), Vec3::Zero());
  const Coded a = EncodeOrDie(*layout, zero, LambdaForStep(1e-3));
  EXPECT_LT(a.bytes.size(), 24u);
  auto d = Decode(*layout, a.bytes.data(), a.bytes.size());
  ASSERT_TRUE(d.ok());
  for (const Vec3& v : *d) EXPECT_EQ(v, Vec3::Zero());
}

TEST(EqCoder, RejectsBadInputs) {
  const SemiRegularHierarchy h = IcoHierarchy(2);
  auto layout = BuildEqLevelLayout(h, 1);
  ASSERT_TRUE(layout.ok());
  std::vector<Vec3> c(layout->size(), Vec3::Zero());
  EqEncodeOptions opt;
  EXPECT_FALSE(EncodeEqLevel(*layout, std::vector<Vec3>(3), kQ0, opt, nullptr).ok());
  EXPECT_FALSE(EncodeEqLevel(*layout, c, 0.0, opt, nullptr).ok());
  c[3] = Vec3(NAN, 0, 0);
  EXPECT_FALSE(EncodeEqLevel(*layout, c, kQ0, opt, nullptr).ok());
  c[3] = Vec3(1e9, 0, 0);  // 2^27 quanta exceeded
  EXPECT_EQ(EncodeEqLevel(*layout, c, kQ0, opt, nullptr).status().code(), StatusCode::kInvalidArgument);
}

TEST(EqDecoder, EveryTruncatedPrefixIsRejected) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  const Coded a = EncodeOrDie(*layout, SyntheticCoefficients(h, 2, 3), LambdaForStep(1e-4));
  ASSERT_GT(a.bytes.size(), 100u);
  for (size_t len = 0; len < a.bytes.size(); ++len) {
    auto d = Decode(*layout, a.bytes.data(), len);
    ASSERT_FALSE(d.ok()) << "prefix " << len << " of " << a.bytes.size();
    EXPECT_EQ(d.status().code(), StatusCode::kCorruptStream);
  }
}

// A finished chunk is consumed exactly (ext_spec A.4.1), so bytes after it are
// refused rather than silently ignored.
TEST(EqDecoder, BytesLeftOverAreRejected) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  for (double step : {1e-2, 1e-4}) {
    const Coded a = EncodeOrDie(*layout, SyntheticCoefficients(h, 2, 5), LambdaForStep(step));
    ASSERT_TRUE(Decode(*layout, a.bytes.data(), a.bytes.size()).ok());
    for (const uint8_t extra : {uint8_t{0x00}, uint8_t{0x5a}, uint8_t{0xff}}) {
      std::vector<uint8_t> padded = a.bytes;
      padded.push_back(extra);
      auto d = Decode(*layout, padded.data(), padded.size());
      ASSERT_FALSE(d.ok()) << "step " << step << " extra " << int{extra};
      EXPECT_EQ(d.status().code(), StatusCode::kCorruptStream);
      EXPECT_NE(d.status().message().find("left over"), std::string::npos) << d.status().ToString();
    }
  }
}

TEST(EqDecoder, GarbageAndBitFlipsNeverCrash) {
  const SemiRegularHierarchy h = IcoHierarchy(4);
  auto layout = BuildEqLevelLayout(h, 3);
  ASSERT_TRUE(layout.ok());
  const Coded a = EncodeOrDie(*layout, SyntheticCoefficients(h, 3, 4), LambdaForStep(1e-4));
  std::mt19937 rng(99);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes;
    if (trial % 2 == 0) {
      bytes.resize(rng() % 4096);
      for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    } else {
      bytes = a.bytes;
      for (int f = 0; f < 1 + trial % 5; ++f) bytes[rng() % bytes.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
    }
    auto d = Decode(*layout, bytes.data(), bytes.size());
    if (d.ok()) {
      ASSERT_EQ(d->size(), layout->size());
      for (const Vec3& v : *d) ASSERT_LE(v.cwiseAbs().maxCoeff(), static_cast<double>(kEqMaxCoefficient) * kQ0);
    }
  }
  EXPECT_FALSE(Decode(*layout, nullptr, 0).ok());
}

// A level whose all-zero-neighbourhood quantizers code nothing is all zero; the
// decoder sees that from the side information alone and builds no layout.
TEST(EqDecoder, LevelsThatCodeNothingAreRecognisedFromTheSideInformation) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  const uint32_t count = static_cast<uint32_t>(layout->size());
  for (const bool context : {true, false}) {
    const Coded zero = EncodeOrDie(*layout, std::vector<Vec3>(count, Vec3::Zero()), LambdaForStep(1e-3), context);
    auto nothing = EqLevelCodesNothing(zero.bytes.data(), zero.bytes.size(), count, context, 2);
    ASSERT_TRUE(nothing.ok()) << nothing.status().ToString();
    EXPECT_TRUE(*nothing);
    auto full = Decode(*layout, zero.bytes.data(), zero.bytes.size(), context);
    ASSERT_TRUE(full.ok());
    for (const Vec3& v : *full) EXPECT_EQ(v, Vec3::Zero());
    std::vector<uint8_t> padded = zero.bytes;
    padded.push_back(0x5a);
    EXPECT_FALSE(EqLevelCodesNothing(padded.data(), padded.size(), count, context, 2).ok());
    EXPECT_FALSE(Decode(*layout, padded.data(), padded.size(), context).ok());
    const Coded some = EncodeOrDie(*layout, SyntheticCoefficients(h, 2, 7), LambdaForStep(1e-4), context);
    auto coded = EqLevelCodesNothing(some.bytes.data(), some.bytes.size(), count, context, 2);
    ASSERT_TRUE(coded.ok());
    EXPECT_FALSE(*coded);
    EXPECT_FALSE(*EqLevelCodesNothing(zero.bytes.data(), zero.bytes.size(), count + 1, context, 2));
  }
}

// sigma-hat from 64-bit arithmetic where the sums allow it, 128-bit beyond: both
// must follow the one integer rule of eq_model.h.
TEST(EqModel, SigmaEstimateFollowsTheIntegerRuleForSmallAndHugeValues) {
  const SemiRegularHierarchy h = IcoHierarchy(3);
  auto layout = BuildEqLevelLayout(h, 2);
  ASSERT_TRUE(layout.ok());
  const EqContextTerms terms(*layout, false);
  std::mt19937 rng(5);
  for (const int max_bits : {3, 12, 24, 28}) {
    std::vector<int64_t> recon(layout->size());
    for (int64_t& r : recon) {
      r = static_cast<int64_t>(rng() % (uint32_t{1} << max_bits)) - (int64_t{1} << (max_bits - 1));
    }
    for (size_t p = 0; p < recon.size(); ++p) {
      EqUint128 sum = 0;
      uint64_t weight = 0;
      terms.ForEach(p, [&](size_t n, uint32_t w) {
        sum += static_cast<EqUint128>(static_cast<uint64_t>(recon[n] * recon[n])) * w;
        weight += w;
      });
      int32_t got = 0;
      const bool predictable = EstimateLogSigma2(recon.data(), terms, p, &got);
      ASSERT_EQ(predictable, sum != 0);
      if (!predictable) continue;
      EqUint128 mean = (sum << 16) / weight;
      if (mean == 0) mean = 1;
      const double log2_mean = std::log2(static_cast<double>(mean));
      const int32_t expected = std::clamp(Log2Sixteenths(mean) - 256, kEqMinLogSigma2, kEqMaxLogSigma2);
      ASSERT_EQ(got, expected) << "bits " << max_bits << " value " << p;
      ASSERT_NEAR(Log2Sixteenths(mean) / 16.0, log2_mean, 1.0 / 16.0 + 1e-9);
    }
  }
}

}  // namespace
}  // namespace eqmesh

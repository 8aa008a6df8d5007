#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "coding/zerotree/bit_io.h"
#include "coding/zerotree/edge_tree.h"
#include "coding/zerotree/zerotree_coder.h"
#include "test_support.h"

namespace eqmesh {
namespace {

using Coeffs = std::vector<std::vector<Vec3>>;

SemiRegularHierarchy BuildHierarchy(const Mesh& m, int levels) {
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(m.num_vertices()), m.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  return std::move(h).value();
}

// Details decaying ~2^-j with random signs; tangential components 10x smaller.
Coeffs SyntheticCoefficients(const SemiRegularHierarchy& h, int levels, uint32_t seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> expo(1.0);
  auto laplace = [&]() { return (rng() & 1 ? 1.0 : -1.0) * expo(rng); };
  Coeffs c(static_cast<size_t>(levels));
  for (int j = 0; j < levels; ++j) {
    const double sigma = std::ldexp(0.02, -j);
    for (uint32_t k = 0; k < h.NumOddVertices(j); ++k) {
      c[j].push_back(Vec3(sigma * laplace(), 0.1 * sigma * laplace(), 0.1 * sigma * laplace()));
    }
  }
  return c;
}

double Sse(const Coeffs& a, const Coeffs& b) {
  double s = 0;
  for (size_t j = 0; j < a.size(); ++j) {
    for (size_t k = 0; k < a[j].size(); ++k) s += (a[j][k] - b[j][k]).squaredNorm();
  }
  return s;
}

// Bytes of the stream header: 6 fixed bytes and the LEB128 symbol count.
size_t HeaderLength(const std::vector<uint8_t>& bytes) {
  size_t n = 6;
  while (n < bytes.size() && (bytes[n] & 0x80)) ++n;
  return n + 1;
}

ZerotreeOptions Options(double quantum) {
  ZerotreeOptions o;
  o.quantum = quantum;
  o.level_shift = 0;  // error measured on the coefficients themselves
  return o;
}

void ExpectTreeShape(const SemiRegularHierarchy& h, int levels, bool closed) {
  auto tree = zerotree::BuildEdgeTree(h, levels);
  ASSERT_TRUE(tree.ok()) << tree.status().ToString();
  const zerotree::EdgeTree& t = *tree;
  std::vector<int> seen(t.num_nodes(), 0);
  for (uint32_t e = 0; e < t.num_nodes(); ++e) {
    const int level = t.level[e];
    EXPECT_EQ(t.parent[e] == zerotree::kNoParent, level == 0);
    if (level + 1 == levels) {
      EXPECT_EQ(t.ChildCount(e), 0u);
      continue;
    }
    const uint32_t count = t.ChildCount(e);
    if (closed) {
      EXPECT_EQ(count, 4u);
    }
    EXPECT_TRUE(count == 3u || count == 4u) << count;
    uint32_t previous = 0;
    for (uint32_t i = t.child_begin[e]; i < t.child_begin[e + 1]; ++i) {
      const uint32_t c = t.children[i];
      EXPECT_EQ(t.parent[c], e);
      EXPECT_EQ(t.level[c], level + 1);
      EXPECT_GT(c, previous);
      previous = c;
      ++seen[c];
      // Geometry: the child edge shares the parent's midpoint or joins midpoints of
      // the parent's faces; either way it touches the parent edge's neighbourhood.
    }
  }
  for (uint32_t e = t.num_roots(); e < t.num_nodes(); ++e) EXPECT_EQ(seen[e], 1) << e;
}

TEST(EdgeTree, ClosedMeshHasFourChildrenAndOneParent) {
  ExpectTreeShape(BuildHierarchy(testing::MakeIcosphere(0), 4), 4, true);
  ExpectTreeShape(BuildHierarchy(testing::MakeTorus(6, 5), 3), 3, true);
}

TEST(EdgeTree, BoundaryEdgesHaveThreeChildren) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeDisc(2), 3);
  ExpectTreeShape(h, 3, false);
  auto tree = zerotree::BuildEdgeTree(h, 3);
  ASSERT_TRUE(tree.ok());
  // Boundary edges of level j are used by one face: count faces per edge.
  size_t three = 0;
  for (uint32_t k = 0; k < h.NumOddVertices(0); ++k) {
    const Edge& e = h.OddEdge(0, k);
    int faces = 0;
    for (const Face& f : h.Faces(0)) {
      for (int i = 0; i < 3; ++i) {
        const uint32_t a = f[i], b = f[(i + 1) % 3];
        faces += ((a == e[0] && b == e[1]) || (a == e[1] && b == e[0])) ? 1 : 0;
      }
    }
    EXPECT_EQ(tree->ChildCount(k), faces == 1 ? 3u : 4u);
    three += faces == 1 ? 1 : 0;
  }
  EXPECT_GT(three, 0u);
}

TEST(EdgeTree, ChildrenLieOnTheParentEdgeOrItsFaces) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 3);
  auto tree = zerotree::BuildEdgeTree(h, 3);
  ASSERT_TRUE(tree.ok());
  for (int j = 0; j + 1 < 3; ++j) {
    for (uint32_t k = 0; k < h.NumOddVertices(j); ++k) {
      const uint32_t node = tree->level_offset[j] + k;
      const uint32_t mid = h.NumVertices(j) + k;
      int halves = 0;
      for (uint32_t i = tree->child_begin[node]; i < tree->child_begin[node + 1]; ++i) {
        const Edge& ce = h.OddEdge(j + 1, tree->children[i] - tree->level_offset[j + 1]);
        halves += (ce[0] == mid || ce[1] == mid) ? 1 : 0;
      }
      EXPECT_EQ(halves, 2);  // the two halves of the parent edge
    }
  }
}

size_t NoHeader(uint64_t) { return 0; }

// The budget logic relies on the predicted payload size being exact.
TEST(ZerotreeBitIo, PredictedSizeMatchesRangeCoder) {
  std::mt19937 rng(11);
  for (int symbols : {1, 2, 10, 100, 1000, 20000}) {
    zerotree::BudgetedEncoder enc(4, 0, &NoHeader, ~uint64_t{0});
    for (int i = 0; i < symbols; ++i) {
      int bit = (rng() % 10) < 2 ? 1 : 0;
      ASSERT_TRUE(i % 5 == 0 ? enc.Raw(&bit) : enc.Bit(static_cast<int>(rng() % 4), &bit));
    }
    const uint64_t predicted = enc.predicted_bytes();
    EXPECT_EQ(enc.Finish().size(), predicted) << symbols;
  }
}

TEST(Zerotree, UnlimitedBudgetReproducesQuantizedCoefficients) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 4);
  const Coeffs c = SyntheticCoefficients(h, 4, 1);
  for (int shift : {0, 1}) {
    ZerotreeOptions o = Options(1e-5);
    o.level_shift = shift;
    auto bytes = EncodeZerotree(h, c, o);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    auto decoded = DecodeZerotree(h, bytes->data(), bytes->size(), o.quantum, o.tangential_factor);
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    auto quantized = QuantizeZerotree(c, o);
    ASSERT_TRUE(quantized.ok());
    ASSERT_EQ(decoded->size(), quantized->size());
    for (size_t j = 0; j < c.size(); ++j) {
      for (size_t k = 0; k < c[j].size(); ++k) {
        for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ((*decoded)[j][k][i], (*quantized)[j][k][i]);
      }
    }
  }
}

TEST(Zerotree, BoundaryMeshRoundTrip) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeDisc(2), 3);
  const Coeffs c = SyntheticCoefficients(h, 3, 7);
  const ZerotreeOptions o = Options(1e-4);
  auto bytes = EncodeZerotree(h, c, o);
  ASSERT_TRUE(bytes.ok());
  auto decoded = DecodeZerotree(h, bytes->data(), bytes->size(), o.quantum, o.tangential_factor);
  ASSERT_TRUE(decoded.ok());
  EXPECT_DOUBLE_EQ(Sse(*decoded, *QuantizeZerotree(c, o)), 0.0);
}

TEST(Zerotree, PrefixesDecodeWithDecreasingError) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 4);
  const Coeffs c = SyntheticCoefficients(h, 4, 2);
  const ZerotreeOptions o = Options(1e-5);
  auto bytes = EncodeZerotree(h, c, o);
  ASSERT_TRUE(bytes.ok());
  const size_t header = HeaderLength(*bytes);
  double previous = HUGE_VAL;
  for (size_t len = header; len <= bytes->size(); len += std::max<size_t>(1, bytes->size() / 40)) {
    auto decoded = DecodeZerotree(h, bytes->data(), len, o.quantum, o.tangential_factor);
    ASSERT_TRUE(decoded.ok()) << len << ": " << decoded.status().ToString();
    const double e = Sse(*decoded, c);
    EXPECT_LE(e, previous * (1 + 1e-12)) << "prefix " << len;
    previous = e;
  }
  // Every prefix length near the start and near the end decodes.
  for (size_t len = 0; len <= bytes->size(); len += (len > header + 64 && len + 64 < bytes->size()) ? 97 : 1) {
    auto decoded = DecodeZerotree(h, bytes->data(), len, o.quantum, o.tangential_factor);
    EXPECT_EQ(decoded.ok(), len >= header) << len;
  }
}

TEST(Zerotree, BudgetIsExactAndEmbedded) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 4);
  const Coeffs c = SyntheticCoefficients(h, 4, 3);
  ZerotreeOptions o = Options(1e-5);
  auto full = EncodeZerotree(h, c, o);
  ASSERT_TRUE(full.ok());
  double previous = HUGE_VAL;
  for (uint64_t budget : {8, 20, 64, 200, 500, 1000, 2000}) {
    o.byte_budget = budget;
    auto bytes = EncodeZerotree(h, c, o);
    ASSERT_TRUE(bytes.ok()) << bytes.status().ToString();
    EXPECT_LE(bytes->size(), budget);
    EXPECT_GE(bytes->size() + 8, std::min<uint64_t>(budget, full->size())) << "budget " << budget;
    auto decoded = DecodeZerotree(h, bytes->data(), bytes->size(), o.quantum, o.tangential_factor);
    ASSERT_TRUE(decoded.ok());
    const double e = Sse(*decoded, c);
    EXPECT_LE(e, previous);
    previous = e;
  }
  o.byte_budget = 3;
  EXPECT_FALSE(EncodeZerotree(h, c, o).ok());
}

TEST(Zerotree, Deterministic) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 3);
  const Coeffs c = SyntheticCoefficients(h, 3, 4);
  auto a = EncodeZerotree(h, c, Options(1e-5));
  auto b = EncodeZerotree(h, c, Options(1e-5));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, *b);
}

TEST(Zerotree, GarbageNeverCrashes) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 3);
  const Coeffs c = SyntheticCoefficients(h, 3, 5);
  auto bytes = EncodeZerotree(h, c, Options(1e-5));
  ASSERT_TRUE(bytes.ok());
  std::mt19937 rng(9);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> g = *bytes;
    if (trial % 3 == 0) {
      for (auto& b : g) b = static_cast<uint8_t>(rng());
      g[0] = kZerotreeVersion;
    } else {
      for (int f = 0; f < 1 + trial % 7; ++f) g[rng() % g.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
    }
    auto decoded = DecodeZerotree(h, g.data(), g.size() - rng() % g.size(), 1e-5, 100);
    if (decoded.ok()) {
      for (const auto& level : *decoded) {
        for (const Vec3& v : level) EXPECT_TRUE(v.allFinite());
      }
    }
  }
  EXPECT_FALSE(DecodeZerotree(h, nullptr, 0, 1e-5, 100).ok());
}

TEST(Zerotree, RejectsBadArguments) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 2);
  Coeffs c = SyntheticCoefficients(h, 2, 6);
  EXPECT_FALSE(EncodeZerotree(h, c, Options(0)).ok());
  c[1].pop_back();
  EXPECT_FALSE(EncodeZerotree(h, c, Options(1e-5)).ok());
  c = SyntheticCoefficients(h, 2, 6);
  c[0][0].x() = NAN;
  EXPECT_FALSE(EncodeZerotree(h, c, Options(1e-5)).ok());
}

// Bits of plain fixed-length coding at the quantum q: every component gets
// enough bits for its channel's largest integer plus a sign.
double FixedLengthBits(const Coeffs& c, double q) {
  double bits = 0;
  for (int i = 0; i < 3; ++i) {
    double max = 0;
    size_t count = 0;
    for (const auto& level : c) {
      for (const Vec3& v : level) max = std::max(max, std::fabs(std::round(v[i] / q)));
      count += level.size();
    }
    bits += static_cast<double>(count) * (std::ceil(std::log2(max + 1)) + 1);
  }
  return bits;
}

TEST(Zerotree, BeatsFixedLengthCodingAtTheSameError) {
  const SemiRegularHierarchy h = BuildHierarchy(testing::MakeIcosphere(0), 4);
  const Coeffs c = SyntheticCoefficients(h, 4, 8);
  ZerotreeOptions o = Options(1e-4);
  o.tangential_factor = 1;  // same quantum on every channel as the fixed-length code
  auto bytes = EncodeZerotree(h, c, o);
  ASSERT_TRUE(bytes.ok());
  auto decoded = DecodeZerotree(h, bytes->data(), bytes->size(), o.quantum, o.tangential_factor);
  ASSERT_TRUE(decoded.ok());
  // Same integers as uniform rounding at q, hence the same error.
  EXPECT_DOUBLE_EQ(Sse(*decoded, *QuantizeZerotree(c, o)), 0.0);
  const double zt_bits = 8.0 * static_cast<double>(bytes->size());
  const double fixed_bits = FixedLengthBits(c, o.quantum);
  EXPECT_LT(zt_bits, 0.8 * fixed_bits) << zt_bits << " vs " << fixed_bits;
  std::printf("zerotree %.0f bits, fixed-length %.0f bits\n", zt_bits, fixed_bits);
}

}  // namespace
}  // namespace eqmesh

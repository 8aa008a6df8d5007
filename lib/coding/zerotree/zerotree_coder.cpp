// Zerotree coder: see zerotree_coder.h for the papers followed, the stream layout
// and the departures.
#include "coding/zerotree/zerotree_coder.h"

#include <array>
#include <cmath>
#include <string>

#include "coding/entropy/byte_io.h"
#include "coding/zerotree/bit_io.h"
#include "coding/zerotree/edge_tree.h"
#include "coding/zerotree/spiht_engine.h"

namespace eqmesh {
namespace {

using zerotree::ChannelTruth;
using zerotree::EdgeTree;
using zerotree::kChannels;
using zerotree::kMaxPlane;

constexpr size_t kFixedHeaderBytes = 6;
constexpr int kMaxHeaderLevels = 16;
constexpr double kMaxMagnitude = 2199023255551.0;  // 2^41 - 1

size_t HeaderBytes(uint64_t symbols) { return kFixedHeaderBytes + VarintSize(symbols); }

// Integer units per world unit of channel c at level j (see the header).
double Scale(int c, int j, int levels, int level_shift, double quantum, double tangential_factor) {
  const double weight = c == 0 ? 1.0 : 1.0 / std::sqrt(tangential_factor);
  return std::ldexp(weight, level_shift * (levels - 1 - j)) / quantum;
}

bool ValidFactor(double x) { return std::isfinite(x) && x > 0; }

Status ValidateOptions(const std::vector<std::vector<Vec3>>& coeffs, const ZerotreeOptions& o) {
  if (!ValidFactor(o.quantum)) return InvalidArgument("zerotree: quantum must be finite and > 0");
  if (!ValidFactor(o.tangential_factor)) return InvalidArgument("zerotree: tangential factor must be finite and > 0");
  if (o.min_plane < 0 || o.min_plane > kMaxPlane) return InvalidArgument("zerotree: min_plane outside [0, 40]");
  if (o.level_shift < 0 || o.level_shift > kZerotreeMaxLevelShift) {
    return InvalidArgument("zerotree: level_shift outside [0, " + std::to_string(kZerotreeMaxLevelShift) + "]");
  }
  if (coeffs.size() > static_cast<size_t>(kMaxHeaderLevels)) return InvalidArgument("zerotree: too many levels");
  return Status::Ok();
}

// Rounds one component to the integer the stream codes.
StatusOr<int64_t> QuantizeComponent(double value, double scale, int j) {
  const double x = std::round(value * scale);
  if (!std::isfinite(x) || std::fabs(x) > kMaxMagnitude) {
    return InvalidArgument("zerotree: level " + std::to_string(j) +
                           " coefficient is not finite or exceeds 2^41 quanta");
  }
  return static_cast<int64_t>(x);
}

// truth[c].mag/negative from the coefficients, node order of the edge tree.
Status FillTruth(const std::vector<std::vector<Vec3>>& coeffs, const ZerotreeOptions& o, const EdgeTree& tree,
                 std::array<ChannelTruth, kChannels>* truth) {
  const int levels = static_cast<int>(coeffs.size());
  for (ChannelTruth& t : *truth) {
    t.mag.assign(tree.num_nodes(), 0);
    t.negative.assign(tree.num_nodes(), 0);
  }
  for (int j = 0; j < levels; ++j) {
    for (int c = 0; c < kChannels; ++c) {
      const double scale = Scale(c, j, levels, o.level_shift, o.quantum, o.tangential_factor);
      ChannelTruth& t = (*truth)[static_cast<size_t>(c)];
      for (size_t k = 0; k < coeffs[j].size(); ++k) {
        EQMESH_ASSIGN_OR_RETURN(const int64_t q, QuantizeComponent(coeffs[j][k][c], scale, j));
        const size_t node = tree.level_offset[j] + k;
        t.mag[node] = static_cast<uint64_t>(q < 0 ? -q : q);
        t.negative[node] = q < 0 ? 1 : 0;
      }
    }
  }
  return Status::Ok();
}

// Descendant maxima bottom-up: children always have larger node ids.
void FillSetMaxima(const EdgeTree& tree, ChannelTruth* t) {
  t->desc_max.assign(tree.num_nodes(), 0);
  t->grandchild_max.assign(tree.num_nodes(), 0);
  for (uint32_t e = tree.num_nodes(); e-- > 0;) {
    for (uint32_t i = tree.child_begin[e]; i < tree.child_begin[e + 1]; ++i) {
      const uint32_t child = tree.children[i];
      t->desc_max[e] = std::max({t->desc_max[e], t->mag[child], t->desc_max[child]});
      t->grandchild_max[e] = std::max(t->grandchild_max[e], t->desc_max[child]);
    }
  }
}

int TopPlane(const ChannelTruth& t) {
  uint64_t m = 0;
  for (uint64_t v : t.mag) m = std::max(m, v);
  int top = -1;
  while (m != 0) {
    m >>= 1;
    ++top;
  }
  return top;
}

std::vector<uint8_t> AssembleStream(int levels, int level_shift, const std::array<int, kChannels>& tops,
                                    uint64_t symbols, const std::vector<uint8_t>& payload) {
  ByteWriter out;
  out.PutU8(kZerotreeVersion);
  out.PutU8(static_cast<uint8_t>(levels));
  out.PutU8(static_cast<uint8_t>(level_shift));
  for (int top : tops) out.PutU8(static_cast<uint8_t>(top + 1));
  out.PutVarint(symbols);
  out.PutBytes(payload);
  return out.Take();
}

struct EncodeSetup {
  EdgeTree tree;
  std::array<ChannelTruth, kChannels> truth;
  std::array<int, kChannels> tops{};
};

// One coding run limited by budget and symbol count; returns the whole stream.
std::vector<uint8_t> RunEncoder(const EncodeSetup& setup, const ZerotreeOptions& o, uint64_t symbol_limit,
                                uint64_t* symbols, int* last_plane = nullptr) {
  zerotree::BudgetedEncoder sink(zerotree::kNumContexts, o.byte_budget, &HeaderBytes, symbol_limit);
  zerotree::SpihtEngine<zerotree::BudgetedEncoder> engine(setup.tree, setup.tops, setup.truth.data(), &sink);
  const int plane = engine.Run(o.min_plane);
  if (last_plane) *last_plane = plane;
  *symbols = sink.symbols();
  return AssembleStream(setup.tree.levels, o.level_shift, setup.tops, sink.symbols(), sink.Finish());
}

// The encoder predicts the finished size; should the range coder ever change its
// flush, fall back to the largest symbol count that truly fits.
std::vector<uint8_t> FitBudget(const EncodeSetup& setup, const ZerotreeOptions& o, std::vector<uint8_t> stream,
                               uint64_t symbols) {
  uint64_t lo = 0, hi = symbols;  // lo fits (the header alone does), hi does not
  while (hi - lo > 1) {
    const uint64_t mid = lo + (hi - lo) / 2;
    uint64_t used = 0;
    std::vector<uint8_t> trial = RunEncoder(setup, o, mid, &used);
    if (trial.size() <= o.byte_budget) {
      lo = mid;
      stream = std::move(trial);
    } else {
      hi = mid;
    }
  }
  if (stream.size() > o.byte_budget) stream = RunEncoder(setup, o, lo, &symbols);
  return stream;
}

Status ValidateShapes(const SemiRegularHierarchy& h, const std::vector<std::vector<Vec3>>& coeffs) {
  if (coeffs.size() > static_cast<size_t>(h.levels())) {
    return InvalidArgument("zerotree: " + std::to_string(coeffs.size()) + " coefficient levels for a hierarchy of " +
                           std::to_string(h.levels()));
  }
  for (size_t j = 0; j < coeffs.size(); ++j) {
    if (coeffs[j].size() != h.NumOddVertices(static_cast<int>(j))) {
      return InvalidArgument("zerotree: level " + std::to_string(j) + " has " + std::to_string(coeffs[j].size()) +
                             " coefficients, expected " + std::to_string(h.NumOddVertices(static_cast<int>(j))));
    }
  }
  return Status::Ok();
}

}  // namespace

size_t ZerotreeMinBytes() { return HeaderBytes(0); }

bool ZerotreeHeaderComplete(const uint8_t* data, size_t size) {
  if (data == nullptr || size <= kFixedHeaderBytes) return false;
  for (size_t i = kFixedHeaderBytes; i < size; ++i) {
    if ((data[i] & 0x80) == 0) return true;  // last byte of the symbol count
  }
  return false;
}

StatusOr<std::vector<uint8_t>> EncodeZerotree(const SemiRegularHierarchy& hierarchy,
                                              const std::vector<std::vector<Vec3>>& coeffs,
                                              const ZerotreeOptions& options, ZerotreeEncodeReport* report) {
  EQMESH_RETURN_IF_ERROR(ValidateOptions(coeffs, options));
  EQMESH_RETURN_IF_ERROR(ValidateShapes(hierarchy, coeffs));
  if (options.byte_budget != 0 && options.byte_budget < HeaderBytes(0)) {
    return InvalidArgument("zerotree: byte budget " + std::to_string(options.byte_budget) +
                           " below the header size " + std::to_string(HeaderBytes(0)));
  }
  EncodeSetup setup;
  EQMESH_ASSIGN_OR_RETURN(setup.tree, zerotree::BuildEdgeTree(hierarchy, static_cast<int>(coeffs.size())));
  EQMESH_RETURN_IF_ERROR(FillTruth(coeffs, options, setup.tree, &setup.truth));
  for (int c = 0; c < kChannels; ++c) {
    FillSetMaxima(setup.tree, &setup.truth[static_cast<size_t>(c)]);
    setup.tops[static_cast<size_t>(c)] = TopPlane(setup.truth[static_cast<size_t>(c)]);
  }
  uint64_t symbols = 0;
  int last_plane = 0;
  std::vector<uint8_t> stream = RunEncoder(setup, options, ~uint64_t{0}, &symbols, &last_plane);
  if (options.byte_budget != 0 && stream.size() > options.byte_budget) {
    stream = FitBudget(setup, options, std::move(stream), symbols);
  }
  if (report) report->last_plane = last_plane;
  return stream;
}

StatusOr<int> ReadZerotreeHeaderLevels(const uint8_t* data, size_t size) {
  if (data == nullptr || size < kFixedHeaderBytes + 1) {
    return CorruptStream("zerotree stream: " + std::to_string(size) + " bytes, shorter than its header");
  }
  if (data[0] != kZerotreeVersion) {
    return UnsupportedVersion("zerotree stream: version " + std::to_string(data[0]) + ", this build reads " +
                              std::to_string(kZerotreeVersion));
  }
  return int{data[1]};
}

namespace {

struct StreamHeader {
  int levels = 0;
  int level_shift = 0;
  std::array<int, kChannels> tops{};
  uint64_t symbols = 0;
  size_t payload_offset = 0;
};

StatusOr<StreamHeader> ParseHeader(const SemiRegularHierarchy& h, const uint8_t* data, size_t size) {
  StreamHeader hdr;
  EQMESH_ASSIGN_OR_RETURN(hdr.levels, ReadZerotreeHeaderLevels(data, size));
  hdr.level_shift = data[2];
  if (hdr.levels > h.levels()) {
    return CorruptStream("zerotree stream: " + std::to_string(hdr.levels) + " levels, hierarchy has " +
                         std::to_string(h.levels()));
  }
  if (hdr.level_shift > kZerotreeMaxLevelShift) return CorruptStream("zerotree stream: level shift out of range");
  for (int c = 0; c < kChannels; ++c) {
    const int top = data[3 + c] - 1;
    if (top > kMaxPlane) return CorruptStream("zerotree stream: top bit plane out of range");
    hdr.tops[static_cast<size_t>(c)] = top;
  }
  ByteReader reader(data + kFixedHeaderBytes, size - kFixedHeaderBytes, "zerotree stream symbol count");
  EQMESH_RETURN_IF_ERROR(reader.ReadVarint(&hdr.symbols));
  hdr.payload_offset = kFixedHeaderBytes + reader.offset();
  return hdr;
}

double Reconstruct(const zerotree::ChannelState& s, uint32_t e) {
  if (!s.sig[e]) return 0;
  const double half_width = (std::ldexp(1.0, s.plane[e]) - 1) / 2;
  const double v = static_cast<double>(s.mag[e]) + half_width;
  return s.negative[e] ? -v : v;
}

}  // namespace

StatusOr<std::vector<std::vector<Vec3>>> DecodeZerotree(const SemiRegularHierarchy& hierarchy,
                                                        const uint8_t* data, size_t size, double quantum,
                                                        double tangential_factor) {
  if (!ValidFactor(quantum) || !ValidFactor(tangential_factor)) {
    return InvalidArgument("zerotree: quantum and tangential factor must be finite and > 0");
  }
  EQMESH_ASSIGN_OR_RETURN(const StreamHeader hdr, ParseHeader(hierarchy, data, size));
  EQMESH_ASSIGN_OR_RETURN(const EdgeTree tree, zerotree::BuildEdgeTree(hierarchy, hdr.levels));
  zerotree::PrefixDecoder source(zerotree::kNumContexts, data + hdr.payload_offset, size - hdr.payload_offset,
                                 hdr.symbols);
  zerotree::SpihtEngine<zerotree::PrefixDecoder> engine(tree, hdr.tops, nullptr, &source);
  engine.Run(0);
  std::vector<std::vector<Vec3>> coeffs(static_cast<size_t>(hdr.levels));
  for (int j = 0; j < hdr.levels; ++j) {
    coeffs[j].assign(hierarchy.NumOddVertices(j), Vec3::Zero());
    for (int c = 0; c < kChannels; ++c) {
      const double scale = Scale(c, j, hdr.levels, hdr.level_shift, quantum, tangential_factor);
      for (uint32_t k = 0; k < coeffs[j].size(); ++k) {
        coeffs[j][k][c] = Reconstruct(engine.channel(c), tree.level_offset[j] + k) / scale;
      }
    }
  }
  return coeffs;
}

StatusOr<std::vector<std::vector<Vec3>>> QuantizeZerotree(const std::vector<std::vector<Vec3>>& coeffs,
                                                          const ZerotreeOptions& options) {
  EQMESH_RETURN_IF_ERROR(ValidateOptions(coeffs, options));
  const int levels = static_cast<int>(coeffs.size());
  std::vector<std::vector<Vec3>> out = coeffs;
  for (int j = 0; j < levels; ++j) {
    for (int c = 0; c < kChannels; ++c) {
      const double scale = Scale(c, j, levels, options.level_shift, options.quantum, options.tangential_factor);
      for (Vec3& v : out[j]) {
        EQMESH_ASSIGN_OR_RETURN(const int64_t q, QuantizeComponent(v[c], scale, j));
        v[c] = static_cast<double>(q) / scale;
      }
    }
  }
  return out;
}

}  // namespace eqmesh

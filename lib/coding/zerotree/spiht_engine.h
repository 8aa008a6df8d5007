// Bit-plane set partitioning on the edge quadtree, shared by the zerotree encoder
// and decoder (Said & Pearlman 1996, SPIHT, with Shapiro's 1993 embedded zerotree
// idea; the mesh mapping of Khodakovsky, Schröder, Sweldens 2000 and Khodakovsky &
// Guskov 2003).
//
// One instance runs three scalar channels (normal, tangent, bitangent). Planes run
// from the largest top plane down; at plane n every channel whose top plane is >= n
// does its sorting pass (LIP, then LIS), then every channel refines the LSP entries
// it had before the plane. The stream is therefore embedded across channels: the
// caller scales the tangential channels down so their bits come later.
//
// Departures from SPIHT: every decision is coded with an adaptive binary model
// (contexts below, after notes §3.3) instead of being written raw; signs are raw
// bits; the descendant sets follow the edge quadtree (3 or 4 children, roots =
// base edges, every root with children starts in the LIS as type A). A coefficient
// becomes significant only once its sign is coded, so a stream that ends between
// the two leaves the coefficient at zero.
//
// Coder concept (BudgetedEncoder / PrefixDecoder): bool Bit(int ctx, int* bit),
// bool Raw(int* bit); false ends the run. The encoder passes the true bit in *bit,
// the decoder receives it there.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "coding/zerotree/edge_tree.h"

namespace eqmesh::zerotree {

constexpr int kChannels = 3;
constexpr int kMaxPlane = 40;  // magnitudes are < 2^(kMaxPlane + 1)

// Context layout per channel: significance (level bucket x parent state x
// significant siblings), set significance (type x level bucket), refinement.
constexpr int kLevelBuckets = 4;
constexpr int kSigContexts = kLevelBuckets * 3 * 3;
constexpr int kSetContexts = 2 * kLevelBuckets;
constexpr int kRefineContexts = 2;
constexpr int kContextsPerChannel = kSigContexts + kSetContexts + kRefineContexts;
constexpr int kNumContexts = kChannels * kContextsPerChannel;

// What the encoder knows and the decoder learns (integer magnitudes).
struct ChannelTruth {
  std::vector<uint64_t> mag;
  std::vector<uint8_t> negative;
  std::vector<uint64_t> desc_max;       // max magnitude over D(e), 0 if empty
  std::vector<uint64_t> grandchild_max;  // max magnitude over L(e), 0 if empty
};

// Coding state; identical on both sides after every coded symbol.
struct ChannelState {
  int top = -1;                  // first plane coded; -1: channel all zero
  std::vector<uint64_t> mag;     // magnitude bits known so far
  std::vector<int8_t> plane;     // lowest plane known (significant nodes)
  std::vector<int8_t> found;     // plane at which the node became significant
  std::vector<uint8_t> sig, negative;
  std::vector<uint32_t> lip, lsp;
  std::vector<uint64_t> lis;     // node << 1 | type (0: A = D(e), 1: B = L(e))
};

template <typename Coder>
class SpihtEngine {
 public:
  // truth: kChannels entries (encoder) or nullptr (decoder).
  SpihtEngine(const EdgeTree& tree, const std::array<int, kChannels>& tops, const ChannelTruth* truth,
              Coder* coder)
      : tree_(tree), truth_(truth), coder_(coder) {
    for (int c = 0; c < kChannels; ++c) Init(c, tops[static_cast<size_t>(c)]);
  }

  // Codes planes down to min_plane or until the coder refuses a symbol. Returns
  // the plane being coded when the run ended (min_plane when it completed; top + 1
  // when there was nothing to code): rate control reads the R-D slope from it.
  int Run(int min_plane) {
    int top = -1;
    for (const ChannelState& s : state_) top = std::max(top, s.top);
    for (int n = top; n >= min_plane; --n) {
      std::array<size_t, kChannels> old{};
      for (int c = 0; c < kChannels; ++c) old[c] = state_[c].lsp.size();
      for (int c = 0; c < kChannels; ++c) {
        if (n <= state_[c].top && !SortingPass(c, n)) return n;
      }
      for (int c = 0; c < kChannels; ++c) {
        if (!RefinementPass(c, n, old[c])) return n;
      }
    }
    return top >= min_plane ? min_plane : top + 1;
  }

  const ChannelState& channel(int c) const { return state_[c]; }

 private:
  void Init(int c, int top) {
    ChannelState& s = state_[c];
    const size_t n = tree_.num_nodes();
    s.top = top;
    s.mag.assign(n, 0);
    s.plane.assign(n, 0);
    s.found.assign(n, 0);
    s.sig.assign(n, 0);
    s.negative.assign(n, 0);
    for (uint32_t r = 0; r < tree_.num_roots(); ++r) {
      s.lip.push_back(r);
      if (tree_.ChildCount(r) > 0) s.lis.push_back(uint64_t{r} << 1);
    }
  }

  int LevelBucket(uint32_t e) const { return std::min<int>(tree_.level[e], kLevelBuckets - 1); }

  int SigContext(int c, uint32_t e) const {
    const ChannelState& s = state_[c];
    const uint32_t p = tree_.parent[e];
    int parent_state = 2, siblings = 0;
    if (p != kNoParent) {
      parent_state = s.sig[p];
      for (uint32_t i = tree_.child_begin[p]; i < tree_.child_begin[p + 1]; ++i) {
        siblings += (tree_.children[i] != e && s.sig[tree_.children[i]]) ? 1 : 0;
      }
    }
    return c * kContextsPerChannel + (LevelBucket(e) * 3 + parent_state) * 3 + std::min(siblings, 2);
  }
  int SetContext(int c, uint32_t e, int type) const {
    return c * kContextsPerChannel + kSigContexts + type * kLevelBuckets + LevelBucket(e);
  }
  int RefineContext(int c, bool first) const {
    return c * kContextsPerChannel + kSigContexts + kSetContexts + (first ? 1 : 0);
  }

  // Significance of the single coefficient e at plane n (then its sign); sets
  // *significant. False when the coder refused.
  bool CodeNode(int c, uint32_t e, int n, bool* significant) {
    int bit = truth_ ? static_cast<int>((truth_[c].mag[e] >> n) & 1) : 0;
    if (!coder_->Bit(SigContext(c, e), &bit)) return false;
    *significant = bit != 0;
    if (!bit) return true;
    int sign = truth_ ? truth_[c].negative[e] : 0;
    if (!coder_->Raw(&sign)) return false;
    ChannelState& s = state_[c];
    s.sig[e] = 1;
    s.negative[e] = static_cast<uint8_t>(sign);
    s.mag[e] = uint64_t{1} << n;
    s.plane[e] = static_cast<int8_t>(n);
    s.found[e] = static_cast<int8_t>(n);
    s.lsp.push_back(e);
    return true;
  }

  bool SortingPass(int c, int n) { return LipPass(c, n) && LisPass(c, n); }

  bool LipPass(int c, int n) {
    std::vector<uint32_t>& lip = state_[c].lip;
    size_t kept = 0;
    for (size_t i = 0; i < lip.size(); ++i) {
      bool significant = false;
      if (!CodeNode(c, lip[i], n, &significant)) return false;
      if (!significant) lip[kept++] = lip[i];
    }
    lip.resize(kept);
    return true;
  }

  bool SetBit(int c, uint32_t e, int type, int n, bool* significant) {
    int bit = 0;
    if (truth_) {
      const uint64_t m = type == 0 ? truth_[c].desc_max[e] : truth_[c].grandchild_max[e];
      bit = (m >> n) != 0 ? 1 : 0;
    }
    if (!coder_->Bit(SetContext(c, e, type), &bit)) return false;
    *significant = bit != 0;
    return true;
  }

  bool HasGrandchildren(uint32_t e) const {
    for (uint32_t i = tree_.child_begin[e]; i < tree_.child_begin[e + 1]; ++i) {
      if (tree_.ChildCount(tree_.children[i]) > 0) return true;
    }
    return false;
  }

  // Type A set turned significant: code each child, then requeue e as type B.
  bool SplitTypeA(int c, uint32_t e, int n) {
    for (uint32_t i = tree_.child_begin[e]; i < tree_.child_begin[e + 1]; ++i) {
      const uint32_t child = tree_.children[i];
      bool significant = false;
      if (!CodeNode(c, child, n, &significant)) return false;
      if (!significant) state_[c].lip.push_back(child);
    }
    if (HasGrandchildren(e)) state_[c].lis.push_back(uint64_t{e} << 1 | 1);
    return true;
  }

  void SplitTypeB(int c, uint32_t e) {
    for (uint32_t i = tree_.child_begin[e]; i < tree_.child_begin[e + 1]; ++i) {
      state_[c].lis.push_back(uint64_t{tree_.children[i]} << 1);
    }
  }

  // Entries appended while the pass runs are processed in the same pass (SPIHT).
  bool LisPass(int c, int n) {
    std::vector<uint64_t>& lis = state_[c].lis;
    std::vector<uint64_t> remaining;
    for (size_t i = 0; i < lis.size(); ++i) {
      const uint32_t e = static_cast<uint32_t>(lis[i] >> 1);
      const int type = static_cast<int>(lis[i] & 1);
      bool significant = false;
      if (!SetBit(c, e, type, n, &significant)) return false;
      if (!significant) {
        remaining.push_back(lis[i]);
      } else if (type == 0) {
        if (!SplitTypeA(c, e, n)) return false;
      } else {
        SplitTypeB(c, e);
      }
    }
    lis = std::move(remaining);
    return true;
  }

  bool RefinementPass(int c, int n, size_t count) {
    ChannelState& s = state_[c];
    for (size_t i = 0; i < count; ++i) {
      const uint32_t e = s.lsp[i];
      int bit = truth_ ? static_cast<int>((truth_[c].mag[e] >> n) & 1) : 0;
      if (!coder_->Bit(RefineContext(c, s.found[e] == n + 1), &bit)) return false;
      s.mag[e] |= static_cast<uint64_t>(bit) << n;
      s.plane[e] = static_cast<int8_t>(n);
    }
    return true;
  }

  const EdgeTree& tree_;
  const ChannelTruth* truth_;
  Coder* coder_;
  std::array<ChannelState, kChannels> state_;
};

}  // namespace eqmesh::zerotree

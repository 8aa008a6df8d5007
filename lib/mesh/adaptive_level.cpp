// Adaptive extraction of a semi-regular mesh: see adaptive_level.h for the papers
// followed and the departures.
#include "mesh/adaptive_level.h"

#include <algorithm>
#include <optional>
#include <queue>
#include <tuple>
#include <vector>

namespace eqmesh {
namespace {

// Largest deviation of an edge-midpoint vertex from its edge's midpoint anywhere in
// the subtree of each face of levels 0 .. J-1 (the error of leaving it flat).
std::vector<std::vector<double>> SubtreeDeviations(const SemiRegularHierarchy& h, const std::vector<Vec3>& p) {
  const int levels = h.levels();
  std::vector<std::vector<double>> dev(static_cast<size_t>(levels));
  for (int j = levels - 1; j >= 0; --j) {
    const std::vector<Face>& faces = h.Faces(j);
    const std::vector<Face>& fine = h.Faces(j + 1);
    std::vector<double>& d = dev[static_cast<size_t>(j)];
    d.assign(faces.size(), 0.0);
    for (size_t f = 0; f < faces.size(); ++f) {
      const Face& c = faces[f];
      const Face& m = fine[4 * f + 3];  // (m_ab, m_bc, m_ca)
      double worst = 0.0;
      for (int e = 0; e < 3; ++e) {
        const Vec3 mid = 0.5 * (p[c[e]] + p[c[(e + 1) % 3]]);
        worst = std::max(worst, (p[m[e]] - mid).norm());
      }
      if (j + 1 < levels) {
        for (size_t k = 0; k < 4; ++k) worst = std::max(worst, dev[static_cast<size_t>(j) + 1][4 * f + k]);
      }
      d[f] = worst;
    }
  }
  return dev;
}

// One cut through the face forest: which faces are split 1-to-4.
class AdaptiveCut {
 public:
  AdaptiveCut(const SemiRegularHierarchy& h, const std::vector<Vec3>& p, const std::vector<std::vector<double>>& dev)
      : h_(h), p_(p), dev_(dev), levels_(h.levels()), split_(h.NumVertices(h.levels()), 0) {
    refined_.resize(static_cast<size_t>(levels_));
    for (int j = 0; j < levels_; ++j) refined_[static_cast<size_t>(j)].assign(h.Faces(j).size(), 0);
    leaves_ = h.BaseFaces().size();
  }

  // Splits the faces of largest priority while the leaves stay within `target`
  // and a split still reduces the error.
  void RefineByPriority(uint64_t target) {
    using Entry = std::tuple<double, int, uint32_t>;  // priority, -level, -face: larger pops first
    std::priority_queue<Entry> heap;
    auto push = [&](int j, uint32_t f) {
      if (j < levels_) heap.emplace(Priority(j, f), -j, ~f);
    };
    for (uint32_t f = 0; f < h_.BaseFaces().size(); ++f) push(0, f);
    exhausted_ = false;
    while (leaves_ + 3 <= target) {
      if (heap.empty() || !(std::get<0>(heap.top()) > 0.0)) {
        exhausted_ = true;  // nothing left whose split would reduce the error
        break;
      }
      const auto [priority, minus_level, not_face] = heap.top();
      heap.pop();
      const int j = -minus_level;
      const uint32_t f = ~not_face;
      Refine(j, f);
      for (uint32_t k = 0; k < 4; ++k) push(j + 1, 4 * f + k);
    }
  }

  // Balance (no leaf beside leaves two levels finer) and red refinement of leaves
  // with two or three split edges, repeated until neither changes anything; a leaf
  // left with one split edge is then halved (green) when emitted.
  void Close() {
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<std::pair<int, uint32_t>> leaves;
      CollectLeaves(&leaves);
      for (const auto& [j, f] : leaves) {
        if (j >= levels_ || Refined(j, f)) continue;
        if (Unbalanced(j, f) || SplitEdges(j, f, nullptr) >= 2) {
          Refine(j, f);
          changed = true;
        }
      }
    }
  }

  // The priority pass stopped because no split would reduce the error further.
  bool exhausted() const { return exhausted_; }

  uint64_t TriangleCount() const {
    std::vector<std::pair<int, uint32_t>> leaves;
    CollectLeaves(&leaves);
    uint64_t count = 0;
    for (const auto& [j, f] : leaves) count += (j < levels_ && SplitEdges(j, f, nullptr) == 1) ? 2 : 1;
    return count;
  }

  Mesh Emit(AdaptiveLevelReport* report) const {
    std::vector<std::pair<int, uint32_t>> leaves;
    CollectLeaves(&leaves);
    Mesh out;
    out.faces.reserve(leaves.size() + leaves.size() / 4);
    int finest = 0;
    uint64_t greens = 0;
    for (const auto& [j, f] : leaves) {
      finest = std::max(finest, j);
      const Face& c = h_.Faces(j)[f];
      int edge = -1;
      if (j < levels_ && SplitEdges(j, f, &edge) == 1) {
        const uint32_t m = h_.Faces(j + 1)[4 * static_cast<size_t>(f) + 3][static_cast<size_t>(edge)];
        const uint32_t a = c[static_cast<size_t>(edge)], b = c[static_cast<size_t>(edge + 1) % 3],
                       o = c[static_cast<size_t>(edge + 2) % 3];
        out.faces.push_back({a, m, o});
        out.faces.push_back({m, b, o});
        ++greens;
      } else {
        out.faces.push_back(c);
      }
    }
    Renumber(&out);
    if (report) {
      report->green_faces = greens;
      report->finest_level = finest;
      report->refined_faces = refined_count_;
    }
    return out;
  }

 private:
  bool Refined(int j, uint32_t f) const { return j < levels_ && refined_[static_cast<size_t>(j)][f] != 0; }
  // Edge-midpoint vertices (m_ab, m_bc, m_ca) of face f of level j < J.
  const Face& Midpoints(int j, uint32_t f) const { return h_.Faces(j + 1)[4 * static_cast<size_t>(f) + 3]; }

  double Priority(int j, uint32_t f) const {
    const Face& c = h_.Faces(j)[f];
    const double area = 0.5 * (p_[c[1]] - p_[c[0]]).cross(p_[c[2]] - p_[c[0]]).norm();
    const double d = dev_[static_cast<size_t>(j)][f];
    return d * d * area;
  }

  void Refine(int j, uint32_t f) {
    refined_[static_cast<size_t>(j)][f] = 1;
    for (uint32_t m : Midpoints(j, f)) split_[m] = static_cast<uint8_t>(std::min(255, split_[m] + 1));
    leaves_ += 3;
    ++refined_count_;
  }

  // Edges of leaf f (level j < J) whose other side is split; *edge gets the last one.
  int SplitEdges(int j, uint32_t f, int* edge) const {
    int count = 0;
    const Face& m = Midpoints(j, f);
    for (int e = 0; e < 3; ++e) {
      if (split_[m[static_cast<size_t>(e)]] != 0) {
        ++count;
        if (edge) *edge = e;
      }
    }
    return count;
  }

  // Leaf f of level j < J-1 borders, across one of its edges, leaves two levels finer:
  // the other side split a half of that edge. The halves are edges of f's
  // (unsplit) children 0..2, whose midpoints the hierarchy names.
  bool Unbalanced(int j, uint32_t f) const {
    if (j + 1 >= levels_) return false;
    // (child, child edge) of the two halves of f's edges ab, bc, ca.
    static constexpr int kHalves[3][2][2] = {{{0, 0}, {1, 0}}, {{1, 1}, {2, 1}}, {{2, 2}, {0, 2}}};
    const Face& m = Midpoints(j, f);
    for (int e = 0; e < 3; ++e) {
      if (split_[m[static_cast<size_t>(e)]] == 0) continue;
      for (const auto& half : kHalves[e]) {
        const uint32_t child = 4 * f + static_cast<uint32_t>(half[0]);
        if (split_[Midpoints(j + 1, child)[static_cast<size_t>(half[1])]] != 0) return true;
      }
    }
    return false;
  }

  void CollectLeaves(std::vector<std::pair<int, uint32_t>>* leaves) const {
    leaves->clear();
    std::vector<std::pair<int, uint32_t>> stack;
    for (uint32_t f = static_cast<uint32_t>(h_.BaseFaces().size()); f-- > 0;) stack.emplace_back(0, f);
    while (!stack.empty()) {
      const auto [j, f] = stack.back();
      stack.pop_back();
      if (!Refined(j, f)) {
        leaves->emplace_back(j, f);
        continue;
      }
      for (uint32_t k = 4; k-- > 0;) stack.emplace_back(j + 1, 4 * f + k);
    }
  }

  // Keeps the vertices the faces use, in increasing index order.
  void Renumber(Mesh* out) const {
    std::vector<uint32_t> index(p_.size(), 0);
    for (const Face& f : out->faces) {
      for (uint32_t v : f) index[v] = 1;
    }
    uint32_t next = 0;
    for (size_t v = 0; v < index.size(); ++v) {
      if (index[v] == 0) continue;
      index[v] = next++;
      out->positions.push_back(p_[v]);
    }
    for (Face& f : out->faces) {
      for (uint32_t& v : f) v = index[v];
    }
  }

  const SemiRegularHierarchy& h_;
  const std::vector<Vec3>& p_;
  const std::vector<std::vector<double>>& dev_;
  int levels_;
  std::vector<std::vector<uint8_t>> refined_;  // per level < J, per face
  std::vector<uint8_t> split_;                 // per vertex: split faces it is an edge midpoint of
  uint64_t leaves_ = 0;
  uint64_t refined_count_ = 0;
  bool exhausted_ = false;
};

}  // namespace

Mesh ExtractAdaptiveLevel(const SemiRegularMesh& mesh, uint64_t max_triangles, AdaptiveLevelReport* report) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  const uint64_t kept = mesh.kept_exactly.faces.size();
  AdaptiveLevelReport local;
  AdaptiveLevelReport* r = report ? report : &local;
  *r = AdaptiveLevelReport();
  if (h.Faces(h.levels()).size() + kept <= max_triangles) {
    r->finest_level = h.levels();
    return ExtractLevel(mesh, h.levels());
  }
  if (h.BaseFaces().size() + kept >= max_triangles) {
    r->within_budget = h.BaseFaces().size() + kept <= max_triangles;
    return ExtractLevel(mesh, 0);
  }
  const std::vector<std::vector<double>> dev = SubtreeDeviations(h, mesh.positions);
  // Closure adds faces the priority pass does not count, so the pass's target is
  // searched: grown while the closed cut fits, bisected once one does not, and the
  // largest closed cut that fits is kept (within 0.5 % of the budget, or when no
  // split would reduce the error further).
  const uint64_t budget = max_triangles - kept;
  std::optional<AdaptiveCut> best;
  uint64_t best_count = 0, fits = 0, too_big = 0;
  uint64_t target = budget;
  for (int round = 0; round < 24 && target > fits && (too_big == 0 || target < too_big); ++round) {
    AdaptiveCut cut(h, mesh.positions, dev);
    cut.RefineByPriority(target);
    cut.Close();
    const uint64_t count = cut.TriangleCount();
    if (count <= budget) {
      const bool done = cut.exhausted() || budget - count <= budget / 200;
      if (!best || count > best_count) {
        best.emplace(std::move(cut));
        best_count = count;
      }
      if (done) break;
      fits = target;
      target = too_big == 0 ? target + (budget - count) : fits + (too_big - fits) / 2;
    } else {
      too_big = target;
      if (fits == 0) {
        // Shrink in proportion, and at least by a share that doubles every round
        // (closure can cascade when nearly everything is split).
        const uint64_t proportional = target / count * budget + target % count * budget / count;
        target = std::min(proportional, too_big - (too_big >> std::max(1, 6 - round)));
      } else {
        target = fits + (too_big - fits) / 2;
      }
    }
  }
  if (!best) {
    r->within_budget = h.BaseFaces().size() + kept <= max_triangles;
    return ExtractLevel(mesh, 0);
  }
  Mesh out = best->Emit(r);
  AppendKeptComponents(mesh.kept_exactly, &out);
  return out;
}

}  // namespace eqmesh

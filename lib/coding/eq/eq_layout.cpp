// EQ scan layout: see eq_layout.h for the paper followed and the choices made.
#include "coding/eq/eq_layout.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>

namespace eqmesh {
namespace {

using Bary = std::array<int32_t, 3>;  // integer barycentric weights, sum 2^(j+1)

constexpr std::array<std::array<int, 3>, 6> kOrientations = {
    {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};

Bary Mid(const Bary& a, const Bary& b) {
  return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
}

// Corner coordinates of level-j face `local` (index inside its base triangle), found
// by following the child digits (children 4f+0..3, see semi_regular.h) from the base.
std::array<Bary, 3> FaceCorners(uint64_t local, int j, int32_t n) {
  std::array<Bary, 3> c = {Bary{n, 0, 0}, Bary{0, n, 0}, Bary{0, 0, n}};
  for (int d = j - 1; d >= 0; --d) {
    const int child = static_cast<int>((local >> (2 * d)) & 3);
    const Bary ab = Mid(c[0], c[1]), bc = Mid(c[1], c[2]), ca = Mid(c[2], c[0]);
    switch (child) {
      case 0: c = {c[0], ab, ca}; break;
      case 1: c = {ab, c[1], bc}; break;
      case 2: c = {ca, bc, c[2]}; break;
      default: c = {ab, bc, ca}; break;
    }
  }
  return c;
}

// Same-scale adjacency (CSR) of the odd vertices: the edges of every middle child.
void BuildOddAdjacency(const SemiRegularHierarchy& h, int j, std::vector<uint32_t>* offsets,
                       std::vector<uint32_t>* adj) {
  const uint32_t first = h.NumVertices(j);
  const uint32_t count = h.NumOddVertices(j);
  const std::vector<Face>& fine = h.Faces(j + 1);
  const size_t coarse_faces = h.Faces(j).size();
  std::vector<uint32_t> degree(count + 1, 0);
  for (size_t f = 0; f < coarse_faces; ++f) {
    for (uint32_t v : fine[4 * f + 3]) degree[v - first] += 2;
  }
  offsets->assign(count + 1, 0);
  for (uint32_t k = 0; k < count; ++k) (*offsets)[k + 1] = (*offsets)[k] + degree[k];
  adj->assign((*offsets)[count], 0);
  std::vector<uint32_t> fill(offsets->begin(), offsets->end() - 1);
  for (size_t f = 0; f < coarse_faces; ++f) {
    const Face& m = fine[4 * f + 3];
    for (int a = 0; a < 3; ++a) {
      const uint32_t u = m[a] - first, w = m[(a + 1) % 3] - first;
      (*adj)[fill[u]++] = w;
      (*adj)[fill[w]++] = u;
    }
  }
}

// Breadth-first order of the base faces over shared edges (see eq_layout.h).
std::vector<uint32_t> BaseFaceOrder(const std::vector<Face>& faces) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edge_faces;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (int a = 0; a < 3; ++a) {
      const uint32_t u = faces[f][a], v = faces[f][(a + 1) % 3];
      edge_faces[{std::min(u, v), std::max(u, v)}].push_back(f);
    }
  }
  std::vector<uint8_t> visited(faces.size(), 0);
  std::vector<uint32_t> order;
  order.reserve(faces.size());
  for (uint32_t start = 0; start < faces.size(); ++start) {
    if (visited[start]) continue;
    visited[start] = 1;
    for (size_t head = order.size(), end = (order.push_back(start), order.size()); head < end;
         end = order.size()) {
      for (; head < end; ++head) {
        const Face& f = faces[order[head]];
        for (int a = 0; a < 3; ++a) {
          const uint32_t u = f[a], v = f[(a + 1) % 3];
          for (uint32_t g : edge_faces[{std::min(u, v), std::max(u, v)}]) {
            if (!visited[g]) {
              visited[g] = 1;
              order.push_back(g);
            }
          }
        }
      }
    }
  }
  return order;
}

struct NewVertex {
  uint32_t odd;
  Bary w;
};

int64_t ScanKey(const Bary& w, const std::array<int, 3>& o, int32_t n) {
  return static_cast<int64_t>(w[o[2]]) * (n + 1) + w[o[1]];
}

class LayoutBuilder {
 public:
  LayoutBuilder(const SemiRegularHierarchy& h, int j) : h_(h), j_(j) {
    BuildOddAdjacency(h, j, &adj_offsets_, &adj_);
    const uint32_t count = h.NumOddVertices(j);
    assigned_.assign(count, 0);
    slot_.assign(count, UINT32_MAX);
  }

  EqLevelLayout Build() {
    EqLevelLayout layout;
    layout.level = j_;
    layout.first_vertex = h_.NumVertices(j_);
    for (uint32_t t : BaseFaceOrder(h_.BaseFaces())) ScanBaseTriangle(t, &layout.scan);
    layout.rank.assign(layout.scan.size(), 0);
    for (uint32_t i = 0; i < layout.scan.size(); ++i) layout.rank[layout.scan[i]] = i;
    BuildNeighbourhoods(&layout);
    return layout;
  }

 private:
  // New (not yet scanned) odd vertices of base triangle t with their coordinates.
  std::vector<NewVertex> CollectNew(size_t t) {
    const uint64_t per_base = uint64_t{1} << (2 * j_);
    const int32_t n = int32_t{1} << (j_ + 1);
    const std::vector<Face>& fine = h_.Faces(j_ + 1);
    const uint32_t first = h_.NumVertices(j_);
    std::vector<NewVertex> out;
    for (uint64_t local = 0; local < per_base; ++local) {
      const uint64_t f = t * per_base + local;
      const std::array<Bary, 3> c = FaceCorners(local, j_, n);
      const Face& m = fine[static_cast<size_t>(4 * f + 3)];  // (m_ab, m_bc, m_ca)
      const std::array<Bary, 3> mw = {Mid(c[0], c[1]), Mid(c[1], c[2]), Mid(c[2], c[0])};
      for (int a = 0; a < 3; ++a) {
        const uint32_t k = m[a] - first;
        if (assigned_[k] || slot_[k] != UINT32_MAX) continue;
        slot_[k] = static_cast<uint32_t>(out.size());
        out.push_back({k, mw[a]});
      }
    }
    return out;
  }

  // Total causal first-ring neighbours of the new vertices under orientation o.
  int64_t CausalCount(const std::vector<NewVertex>& verts, const std::array<int, 3>& o, int32_t n) {
    int64_t count = 0;
    for (const NewVertex& v : verts) {
      const int64_t key = ScanKey(v.w, o, n);
      for (uint32_t e = adj_offsets_[v.odd]; e < adj_offsets_[v.odd + 1]; ++e) {
        const uint32_t u = adj_[e];
        if (assigned_[u]) {
          ++count;
        } else if (slot_[u] != UINT32_MAX && ScanKey(verts[slot_[u]].w, o, n) < key) {
          ++count;
        }
      }
    }
    return count;
  }

  void ScanBaseTriangle(size_t t, std::vector<uint32_t>* scan) {
    const int32_t n = int32_t{1} << (j_ + 1);
    std::vector<NewVertex> verts = CollectNew(t);
    int best = 0;
    int64_t best_count = -1;
    for (int o = 0; o < 6; ++o) {
      const int64_t c = CausalCount(verts, kOrientations[o], n);
      if (c > best_count) {
        best_count = c;
        best = o;
      }
    }
    const std::array<int, 3>& o = kOrientations[best];
    std::sort(verts.begin(), verts.end(), [&](const NewVertex& a, const NewVertex& b) {
      return ScanKey(a.w, o, n) < ScanKey(b.w, o, n);
    });
    for (const NewVertex& v : verts) {
      scan->push_back(v.odd);
      assigned_[v.odd] = 1;
      slot_[v.odd] = UINT32_MAX;
    }
  }

  // Breadth-first rings 1..3 over the same-scale graph, keeping causal vertices.
  void BuildNeighbourhoods(EqLevelLayout* layout) {
    const uint32_t count = static_cast<uint32_t>(layout->scan.size());
    std::vector<uint32_t> seen(count, UINT32_MAX);
    std::vector<uint32_t> frontier, next;
    // About 12 causal neighbours a vertex on a regular level: reserving once keeps
    // the finest level's arrays from being copied as they grow.
    layout->offsets.reserve(static_cast<size_t>(count) + 1);
    layout->neighbours.reserve(static_cast<size_t>(count) * 13);
    layout->ring.reserve(static_cast<size_t>(count) * 13);
    layout->offsets.assign(1, 0);
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t k = layout->scan[i];
      seen[k] = i;
      frontier.assign(1, k);
      for (uint8_t r = 1; r <= 3; ++r) {
        next.clear();
        for (uint32_t v : frontier) {
          for (uint32_t e = adj_offsets_[v]; e < adj_offsets_[v + 1]; ++e) {
            const uint32_t u = adj_[e];
            if (seen[u] == i) continue;
            seen[u] = i;
            next.push_back(u);
            if (layout->rank[u] < i) {
              layout->neighbours.push_back(layout->rank[u]);
              layout->ring.push_back(r);
            }
          }
        }
        frontier.swap(next);
      }
      layout->offsets.push_back(static_cast<uint32_t>(layout->neighbours.size()));
    }
  }

  const SemiRegularHierarchy& h_;
  int j_;
  std::vector<uint32_t> adj_offsets_, adj_;
  std::vector<uint8_t> assigned_;
  std::vector<uint32_t> slot_;  // index in the current triangle's new list
};

}  // namespace

StatusOr<EqLevelLayout> BuildEqLevelLayout(const SemiRegularHierarchy& hierarchy, int j) {
  if (j < 0 || j >= hierarchy.levels()) {
    return InvalidArgument("EQ level " + std::to_string(j) + " outside [0, " +
                           std::to_string(hierarchy.levels()) + ")");
  }
  EqLevelLayout layout = LayoutBuilder(hierarchy, j).Build();
  if (layout.size() != hierarchy.NumOddVertices(j)) {
    return InternalError("EQ scan covers " + std::to_string(layout.size()) + " of " +
                         std::to_string(hierarchy.NumOddVertices(j)) + " odd vertices");
  }
  return layout;
}

}  // namespace eqmesh

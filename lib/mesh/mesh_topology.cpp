// Adjacency construction: counting sort of half-edges by smaller endpoint
// (libigl edge_topology style, without the per-edge map), CSR vertex stars,
// union-find face components, fan-walking boundary loops.
#include "mesh/mesh_topology.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace eqmesh {
namespace {

// Half-edge ids are uint32_t; faces past this bound cannot be addressed.
constexpr size_t kMaxFaces = (0xffffffffu / 3u) - 1u;

uint32_t Find(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];  // path halving keeps trees shallow
    x = parent[x];
  }
  return x;
}

void Union(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
  a = Find(parent, a);
  b = Find(parent, b);
  // Lower id wins so roots, and hence labels, do not depend on visit order.
  if (a < b) parent[b] = a;
  else if (b < a) parent[a] = b;
}

// Exclusive prefix sum of counts[0..n) into offsets[0..n].
std::vector<uint32_t> PrefixOffsets(const std::vector<uint32_t>& counts) {
  std::vector<uint32_t> offsets(counts.size() + 1, 0);
  for (size_t i = 0; i < counts.size(); ++i) offsets[i + 1] = offsets[i] + counts[i];
  return offsets;
}

}  // namespace

uint32_t LabelFans(uint32_t center, const std::vector<Face>& star, const std::vector<uint8_t>& cut_masks,
                   std::vector<uint32_t>* labels) {
  const uint32_t d = static_cast<uint32_t>(star.size());
  labels->assign(d, 0);
  if (d == 0) return 0;
  // (other endpoint, local face) for both star edges of every face; faces with
  // the same other endpoint share that edge.
  thread_local std::vector<std::pair<uint32_t, uint32_t>> spokes;
  spokes.clear();
  for (uint32_t i = 0; i < d; ++i) {
    const Face& t = star[i];
    const int c = t[0] == center ? 0 : (t[1] == center ? 1 : 2);
    const unsigned mask = cut_masks.empty() ? 0u : cut_masks[i];
    const int out = c, in = (c + 2) % 3;  // edges (center, next) and (prev, center)
    if (!(mask & (1u << out))) spokes.emplace_back(t[(c + 1) % 3], i);
    if (!(mask & (1u << in))) spokes.emplace_back(t[(c + 2) % 3], i);
  }
  std::sort(spokes.begin(), spokes.end());
  thread_local std::vector<uint32_t> parent;
  parent.resize(d);
  std::iota(parent.begin(), parent.end(), 0u);
  for (size_t k = 1; k < spokes.size(); ++k)
    if (spokes[k].first == spokes[k - 1].first) Union(parent, spokes[k].second, spokes[k - 1].second);
  // Roots are the lowest member, so first appearance of a root is its label.
  uint32_t count = 0;
  for (uint32_t i = 0; i < d; ++i) {
    const uint32_t root = Find(parent, i);
    (*labels)[i] = root == i ? count++ : (*labels)[root];
  }
  return count;
}

MeshTopology::MeshTopology(const Mesh& mesh)
    : num_vertices_(mesh.positions.size()), faces_(mesh.faces) {
  MarkUsableFaces();
  BuildEdges();
  BuildVertexStars();
  BuildComponents();
}

void MeshTopology::MarkUsableFaces() {
  usable_.assign(faces_.size(), 0);
  for (size_t f = 0; f < faces_.size(); ++f) {
    const Face& t = faces_[f];
    const bool in_range = t[0] < num_vertices_ && t[1] < num_vertices_ && t[2] < num_vertices_;
    const bool distinct = t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
    usable_[f] = (in_range && distinct && f < kMaxFaces) ? 1 : 0;
    if (!usable_[f]) ++num_unusable_;
  }
}

void MeshTopology::BuildEdges() {
  const uint32_t num_halfedges = static_cast<uint32_t>(std::min(faces_.size(), kMaxFaces) * 3);
  halfedge_edge_.assign(faces_.size() * 3, kNone);
  // Bucket half-edges by their smaller endpoint.
  std::vector<uint32_t> counts(num_vertices_, 0);
  for (uint32_t h = 0; h < num_halfedges; ++h) {
    if (!usable_[h / 3]) continue;
    ++counts[std::min(HalfedgeFrom(h), HalfedgeTo(h))];
  }
  std::vector<uint32_t> bucket = PrefixOffsets(counts);
  std::vector<uint32_t> sorted(bucket.back());
  std::vector<uint32_t> cursor(bucket.begin(), bucket.end() - 1);
  for (uint32_t h = 0; h < num_halfedges; ++h) {
    if (!usable_[h / 3]) continue;
    sorted[cursor[std::min(HalfedgeFrom(h), HalfedgeTo(h))]++] = h;
  }
  // Inside a bucket order by larger endpoint, then half-edge id (deterministic).
  auto larger = [this](uint32_t h) { return std::max(HalfedgeFrom(h), HalfedgeTo(h)); };
  edge_halfedges_.clear();
  edge_halfedges_.reserve(sorted.size());
  edge_offsets_.assign(1, 0);
  edges_.clear();
  for (size_t v = 0; v < num_vertices_; ++v) {
    auto first = sorted.begin() + bucket[v];
    auto last = sorted.begin() + bucket[v + 1];
    std::sort(first, last, [&](uint32_t a, uint32_t b) {
      const uint32_t la = larger(a), lb = larger(b);
      return la != lb ? la < lb : a < b;
    });
    for (auto it = first; it != last; ++it) {
      const uint32_t other = larger(*it);
      if (it == first || larger(*(it - 1)) != other) {
        if (it != first) edge_offsets_.push_back(static_cast<uint32_t>(edge_halfedges_.size()));
        edges_.push_back({static_cast<uint32_t>(v), other});
      }
      halfedge_edge_[*it] = static_cast<uint32_t>(edges_.size() - 1);
      edge_halfedges_.push_back(*it);
    }
    if (first != last) edge_offsets_.push_back(static_cast<uint32_t>(edge_halfedges_.size()));
  }
}

void MeshTopology::BuildVertexStars() {
  std::vector<uint32_t> counts(num_vertices_, 0);
  for (size_t f = 0; f < faces_.size(); ++f)
    if (usable_[f])
      for (uint32_t v : faces_[f]) ++counts[v];
  vertex_offsets_ = PrefixOffsets(counts);
  vertex_faces_.assign(vertex_offsets_.back(), 0);
  std::vector<uint32_t> cursor(vertex_offsets_.begin(), vertex_offsets_.end() - 1);
  for (size_t f = 0; f < faces_.size(); ++f)
    if (usable_[f])
      for (uint32_t v : faces_[f]) vertex_faces_[cursor[v]++] = static_cast<uint32_t>(f);
}

void MeshTopology::BuildComponents() {
  std::vector<uint32_t> parent(faces_.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (uint32_t e = 0; e < edges_.size(); ++e) {
    const IndexRange hs = EdgeHalfedges(e);
    for (size_t k = 1; k < hs.size(); ++k) Union(parent, hs[0] / 3, hs[k] / 3);
  }
  face_component_.assign(faces_.size(), kNone);
  std::vector<uint32_t> label_of_root(faces_.size(), kNone);
  num_components_ = 0;
  for (uint32_t f = 0; f < faces_.size(); ++f) {
    if (!usable_[f]) continue;
    const uint32_t root = Find(parent, f);
    if (label_of_root[root] == kNone) label_of_root[root] = static_cast<uint32_t>(num_components_++);
    face_component_[f] = label_of_root[root];
  }
}

bool MeshTopology::IsInconsistentEdge(uint32_t e) const {
  if (EdgeFaceCount(e) != 2) return false;
  const IndexRange hs = EdgeHalfedges(e);
  return HalfedgeFrom(hs[0]) == HalfedgeFrom(hs[1]);
}

uint32_t MeshTopology::FindEdge(uint32_t a, uint32_t b) const {
  if (a > b) std::swap(a, b);
  const Edge key{a, b};
  const auto it = std::lower_bound(edges_.begin(), edges_.end(), key);
  if (it == edges_.end() || *it != key) return kNone;
  return static_cast<uint32_t>(it - edges_.begin());
}

uint32_t MeshTopology::VertexFans(uint32_t v, std::vector<uint32_t>* labels,
                                  const std::vector<uint8_t>* cut_mask) const {
  // Scratch reused across calls: diagnosis asks this for every vertex.
  thread_local std::vector<Face> star;
  thread_local std::vector<uint8_t> masks;
  star.clear();
  masks.clear();
  for (uint32_t f : VertexFaces(v)) {
    star.push_back(faces_[f]);
    if (cut_mask) masks.push_back((*cut_mask)[f]);
  }
  return LabelFans(v, star, masks, labels);
}

OrientationPlan MeshTopology::PlanConsistentOrientation() const {
  OrientationPlan plan;
  plan.flip.assign(faces_.size(), 0);
  std::vector<uint8_t> visited(faces_.size(), 0), in_conflict(edges_.size(), 0);
  std::vector<uint32_t> queue;
  for (uint32_t seed = 0; seed < faces_.size(); ++seed) {
    if (!usable_[seed] || visited[seed]) continue;
    visited[seed] = 1;
    queue.assign(1, seed);
    for (size_t head = 0; head < queue.size(); ++head) {
      const uint32_t f = queue[head];
      for (uint32_t hf = 3 * f; hf < 3 * f + 3; ++hf) {
        const uint32_t e = halfedge_edge_[hf];
        if (EdgeFaceCount(e) != 2) continue;
        const IndexRange hs = EdgeHalfedges(e);
        const uint32_t hg = hs[0] == hf ? hs[1] : hs[0];
        const uint32_t g = hg / 3;
        // Neighbours agree when they run the shared edge in opposite directions.
        const uint8_t same_direction = HalfedgeFrom(hf) == HalfedgeFrom(hg) ? 1 : 0;
        const uint8_t wanted = plan.flip[f] ^ same_direction;
        if (!visited[g]) {
          visited[g] = 1;
          plan.flip[g] = wanted;
          queue.push_back(g);
        } else if (plan.flip[g] != wanted && !in_conflict[e]) {
          in_conflict[e] = 1;
          plan.conflict_edges.push_back(e);
        }
      }
    }
  }
  for (uint8_t x : plan.flip) plan.faces_to_flip += x;
  std::sort(plan.conflict_edges.begin(), plan.conflict_edges.end());
  return plan;
}

// Walks the fan of `at_vertex` from `from_face` (entered across `from_edge`)
// until it meets a boundary edge; kNone when the walk hits a non-manifold edge.
uint32_t MeshTopology::FanWalkToBoundary(uint32_t from_edge, uint32_t from_face,
                                         uint32_t at_vertex) const {
  uint32_t edge = from_edge, face = from_face;
  const size_t max_steps = VertexFaces(at_vertex).size() + 1;
  for (size_t step = 0; step < max_steps; ++step) {
    uint32_t next = kNone;
    for (uint32_t h = 3 * face; h < 3 * face + 3; ++h) {
      const uint32_t e = halfedge_edge_[h];
      if (e != edge && (HalfedgeFrom(h) == at_vertex || HalfedgeTo(h) == at_vertex)) next = e;
    }
    if (next == kNone || EdgeFaceCount(next) > 2) return kNone;
    if (EdgeFaceCount(next) == 1) return next;
    const IndexRange hs = EdgeHalfedges(next);
    face = hs[0] / 3 == face ? hs[1] / 3 : hs[0] / 3;
    edge = next;
  }
  return kNone;
}

// Any unused boundary edge of `component` at vertex v: the fallback where fan
// walking is ambiguous (non-manifold edges).
uint32_t MeshTopology::AnyUnusedBoundaryEdge(uint32_t v, uint32_t component,
                                             const std::vector<uint8_t>& used) const {
  for (uint32_t f : VertexFaces(v)) {
    if (face_component_[f] != component) continue;
    for (uint32_t h = 3 * f; h < 3 * f + 3; ++h) {
      const uint32_t e = halfedge_edge_[h];
      if ((HalfedgeFrom(h) == v || HalfedgeTo(h) == v) && IsBoundaryEdge(e) && !used[e]) return e;
    }
  }
  return kNone;
}

std::vector<BoundaryLoop> MeshTopology::BoundaryLoops() const {
  std::vector<BoundaryLoop> loops;
  std::vector<uint8_t> used(edges_.size(), 0);
  for (uint32_t start_edge = 0; start_edge < edges_.size(); ++start_edge) {
    if (!IsBoundaryEdge(start_edge) || used[start_edge]) continue;
    BoundaryLoop loop;
    const uint32_t h0 = EdgeHalfedges(start_edge)[0];
    const uint32_t start = HalfedgeFrom(h0);
    loop.component = face_component_[h0 / 3];
    loop.vertices.push_back(start);
    loop.edges.push_back(start_edge);
    used[start_edge] = 1;
    uint32_t edge = start_edge, face = h0 / 3, at = HalfedgeTo(h0);
    while (true) {
      uint32_t next = FanWalkToBoundary(edge, face, at);
      if (next == start_edge) break;  // back where we began: a closed loop
      if (next == kNone || used[next]) next = AnyUnusedBoundaryEdge(at, loop.component, used);
      if (next == kNone) {
        loop.closed = (at == start);
        break;
      }
      loop.vertices.push_back(at);
      loop.edges.push_back(next);
      used[next] = 1;
      face = EdgeHalfedges(next)[0] / 3;
      edge = next;
      at = edges_[next][0] == at ? edges_[next][1] : edges_[next][0];
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace eqmesh

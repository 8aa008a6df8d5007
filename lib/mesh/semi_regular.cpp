#include "mesh/semi_regular.h"

#include <algorithm>

namespace eqmesh {
namespace {

// Undirected edges bucketed by their smaller endpoint: a face corner adds at most
// one edge to its bucket, so the buckets are sized by counting corners, and a
// lookup scans a handful of entries instead of hashing.
class EdgeNumbering {
 public:
  EdgeNumbering(uint32_t num_vertices, const std::vector<Face>& faces) {
    uint32_t max_index = 0;
    for (const Face& f : faces) max_index = std::max({max_index, f[0], f[1], f[2]});
    const size_t buckets = std::max<size_t>(num_vertices, size_t{max_index} + 1);
    begin_.assign(buckets + 1, 0);
    for (const Face& f : faces) {
      for (int c = 0; c < 3; ++c) ++begin_[std::min(f[c], f[(c + 1) % 3]) + 1];
    }
    for (size_t v = 0; v < buckets; ++v) begin_[v + 1] += begin_[v];
    fill_.assign(begin_.begin(), begin_.end() - 1);
    other_.resize(begin_.back());
    number_.resize(begin_.back());
  }

  // The number of edge (a, b), given `next` (and *added = true) if it is new.
  uint32_t Find(uint32_t a, uint32_t b, uint32_t next, bool* added) {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    for (uint32_t i = begin_[lo]; i < fill_[lo]; ++i) {
      if (other_[i] == hi) {
        *added = false;
        return number_[i];
      }
    }
    const uint32_t slot = fill_[lo]++;
    other_[slot] = hi;
    number_[slot] = next;
    *added = true;
    return next;
  }

 private:
  std::vector<uint32_t> begin_, fill_, other_, number_;
};

}  // namespace

void SubdivideConnectivity(uint32_t num_vertices, const std::vector<Face>& faces,
                           std::vector<Face>* fine_faces, std::vector<Edge>* odd_edges) {
  EdgeNumbering numbering(num_vertices, faces);
  odd_edges->clear();
  odd_edges->reserve(faces.size() * 3 / 2 + 3);
  fine_faces->clear();
  fine_faces->resize(faces.size() * 4);
  auto odd_vertex = [&](uint32_t a, uint32_t b) {
    bool added = false;
    const uint32_t v = numbering.Find(a, b, num_vertices + static_cast<uint32_t>(odd_edges->size()), &added);
    if (added) odd_edges->push_back({a, b});
    return v;
  };
  Face* out = fine_faces->data();
  for (const Face& f : faces) {
    const uint32_t m01 = odd_vertex(f[0], f[1]);
    const uint32_t m12 = odd_vertex(f[1], f[2]);
    const uint32_t m20 = odd_vertex(f[2], f[0]);
    *out++ = {f[0], m01, m20};
    *out++ = {m01, f[1], m12};
    *out++ = {m20, m12, f[2]};
    *out++ = {m01, m12, m20};
  }
}

uint64_t SemiRegularHierarchy::FinestFaceCount(uint64_t base_faces, int levels) {
  uint64_t count = base_faces;
  for (int j = 0; j < levels; ++j) {
    if (count > (1ull << 60)) return ~0ull;
    count *= 4;
  }
  return count;
}

StatusOr<SemiRegularHierarchy> SemiRegularHierarchy::Build(uint32_t base_vertices,
                                                           std::vector<Face> base_faces, int levels,
                                                           uint64_t max_finest_faces) {
  if (levels < 0 || levels > 16) {
    return InvalidArgument("subdivision level count " + std::to_string(levels) + " outside [0, 16]");
  }
  if (FinestFaceCount(base_faces.size(), levels) > max_finest_faces) {
    return ResourceLimit(std::to_string(base_faces.size()) + " base faces refined " +
                         std::to_string(levels) + " times exceed the limit of " +
                         std::to_string(max_finest_faces) + " faces");
  }
  for (size_t i = 0; i < base_faces.size(); ++i) {
    const Face& f = base_faces[i];
    if (f[0] >= base_vertices || f[1] >= base_vertices || f[2] >= base_vertices) {
      return InvalidMesh("base face " + std::to_string(i) + " references a vertex >= " +
                         std::to_string(base_vertices));
    }
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      return InvalidMesh("base face " + std::to_string(i) + " repeats a vertex");
    }
  }
  SemiRegularHierarchy h;
  h.vertex_counts_.push_back(base_vertices);
  h.faces_.push_back(std::move(base_faces));
  for (int j = 0; j < levels; ++j) EQMESH_RETURN_IF_ERROR(h.Refine(max_finest_faces));
  return h;
}

Status SemiRegularHierarchy::Refine(uint64_t max_finest_faces) {
  if (faces_.empty()) return InvalidArgument("refining a hierarchy that was never built");
  if (levels() >= 16 || FinestFaceCount(faces_.back().size(), 1) > max_finest_faces) {
    return ResourceLimit(std::to_string(faces_.back().size()) + " faces refined once more exceed the limit of " +
                         std::to_string(max_finest_faces) + " faces");
  }
  std::vector<Face> fine;
  std::vector<Edge> odd;
  SubdivideConnectivity(vertex_counts_.back(), faces_.back(), &fine, &odd);
  const uint64_t count = static_cast<uint64_t>(vertex_counts_.back()) + odd.size();
  if (count > 0xFFFFFFF0ull) return ResourceLimit("semi-regular vertex count exceeds 32 bits");
  vertex_counts_.push_back(static_cast<uint32_t>(count));
  faces_.push_back(std::move(fine));
  odd_edges_.push_back(std::move(odd));
  crease_odd_.push_back(TagCreaseOdds(levels() - 1));
  return Status::Ok();
}

namespace {

Edge Undirected(const Edge& e) { return {std::min(e[0], e[1]), std::max(e[0], e[1])}; }

}  // namespace

bool SemiRegularHierarchy::IsBaseCrease(const Edge& e) const {
  return std::binary_search(base_creases_.begin(), base_creases_.end(), Undirected(e));
}

std::vector<uint8_t> SemiRegularHierarchy::TagCreaseOdds(int j) const {
  if (base_creases_.empty()) return {};
  const std::vector<Edge>& odd = odd_edges_[j];
  std::vector<uint8_t> tags(odd.size(), 0);
  if (j == 0) {
    for (size_t k = 0; k < odd.size(); ++k) tags[k] = IsBaseCrease(odd[k]);
    return tags;
  }
  // A level-j edge is half of a tagged level-(j-1) edge when one end is that
  // edge's odd vertex and the other one of its ends.
  const uint32_t first_new = vertex_counts_[j - 1];
  const auto half_of_tagged = [&](uint32_t m, uint32_t other) {
    if (m < first_new) return false;
    const uint32_t parent = m - first_new;
    if (!crease_odd_[j - 1][parent]) return false;
    const Edge& e = odd_edges_[j - 1][parent];
    return other == e[0] || other == e[1];
  };
  for (size_t k = 0; k < odd.size(); ++k) {
    tags[k] = half_of_tagged(odd[k][0], odd[k][1]) || half_of_tagged(odd[k][1], odd[k][0]);
  }
  return tags;
}

Status SemiRegularHierarchy::SetBaseCreases(std::vector<Edge> edges) {
  if (faces_.empty()) return InvalidArgument("crease edges on a hierarchy that was never built");
  if (edges.empty() && base_creases_.empty()) return Status::Ok();  // the common case: nothing to check or retag
  std::vector<Edge> base_edges;
  base_edges.reserve(faces_[0].size() * 3);
  for (const Face& f : faces_[0]) {
    for (int c = 0; c < 3; ++c) base_edges.push_back(Undirected({f[c], f[(c + 1) % 3]}));
  }
  std::sort(base_edges.begin(), base_edges.end());
  for (Edge& e : edges) {
    e = Undirected(e);
    if (!std::binary_search(base_edges.begin(), base_edges.end(), e)) {
      return InvalidMesh("crease edge (" + std::to_string(e[0]) + ", " + std::to_string(e[1]) +
                         ") is not an edge of the base mesh");
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  base_creases_ = std::move(edges);
  for (int j = 0; j < levels(); ++j) crease_odd_[j] = TagCreaseOdds(j);
  return Status::Ok();
}

int SemiRegularHierarchy::VertexLevel(uint32_t v) const {
  int level = 0;
  while (level + 1 < static_cast<int>(vertex_counts_.size()) && v >= vertex_counts_[level]) ++level;
  return level;
}

void AppendKeptComponents(const Mesh& kept, Mesh* out) {
  const uint32_t offset = static_cast<uint32_t>(out->positions.size());
  out->positions.insert(out->positions.end(), kept.positions.begin(), kept.positions.end());
  for (const Face& f : kept.faces) out->faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

Mesh ExtractLevel(const SemiRegularMesh& mesh, int level) {
  Mesh out;
  const uint32_t n = mesh.hierarchy.NumVertices(level);
  out.positions.assign(mesh.positions.begin(), mesh.positions.begin() + n);
  out.faces = mesh.hierarchy.Faces(level);
  AppendKeptComponents(mesh.kept_exactly, &out);
  return out;
}

Mesh ExtractLevel(SemiRegularMesh&& mesh, int level) {
  Mesh out;
  out.positions = std::move(mesh.positions);
  out.positions.resize(mesh.hierarchy.NumVertices(level));
  out.faces = mesh.hierarchy.TakeFaces(level);
  AppendKeptComponents(mesh.kept_exactly, &out);
  return out;
}

}  // namespace eqmesh

#include "mesh/semi_regular.h"

#include <algorithm>
#include <unordered_map>

namespace eqmesh {
namespace {

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<uint64_t>(lo) << 32) | hi;
}

}  // namespace

void SubdivideConnectivity(uint32_t num_vertices, const std::vector<Face>& faces,
                           std::vector<Face>* fine_faces, std::vector<Edge>* odd_edges) {
  std::unordered_map<uint64_t, uint32_t> edge_to_odd;
  edge_to_odd.reserve(faces.size() * 2);
  odd_edges->clear();
  odd_edges->reserve(faces.size() * 3 / 2 + 3);
  fine_faces->clear();
  fine_faces->reserve(faces.size() * 4);
  auto odd_vertex = [&](uint32_t a, uint32_t b) {
    auto [it, inserted] = edge_to_odd.emplace(EdgeKey(a, b), 0u);
    if (inserted) {
      it->second = num_vertices + static_cast<uint32_t>(odd_edges->size());
      odd_edges->push_back({a, b});
    }
    return it->second;
  };
  for (const Face& f : faces) {
    const uint32_t m01 = odd_vertex(f[0], f[1]);
    const uint32_t m12 = odd_vertex(f[1], f[2]);
    const uint32_t m20 = odd_vertex(f[2], f[0]);
    fine_faces->push_back({f[0], m01, m20});
    fine_faces->push_back({m01, f[1], m12});
    fine_faces->push_back({m20, m12, f[2]});
    fine_faces->push_back({m01, m12, m20});
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
  return Status::Ok();
}

int SemiRegularHierarchy::VertexLevel(uint32_t v) const {
  int level = 0;
  while (level + 1 < static_cast<int>(vertex_counts_.size()) && v >= vertex_counts_[level]) ++level;
  return level;
}

Mesh ExtractLevel(const SemiRegularMesh& mesh, int level) {
  Mesh out;
  const SemiRegularHierarchy& h = mesh.hierarchy;
  const uint32_t n = h.NumVertices(level);
  out.positions.assign(mesh.positions.begin(), mesh.positions.begin() + n);
  out.faces = h.Faces(level);
  const uint32_t offset = static_cast<uint32_t>(out.positions.size());
  out.positions.insert(out.positions.end(), mesh.kept_exactly.positions.begin(),
                       mesh.kept_exactly.positions.end());
  for (const Face& f : mesh.kept_exactly.faces) {
    out.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  }
  return out;
}

}  // namespace eqmesh

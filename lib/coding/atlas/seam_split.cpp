#include "coding/atlas/seam_split.h"

#include <cstring>
#include <limits>

namespace eqmesh {
namespace {

// The two faces of an edge compute its midpoint as a + b and as b + a; IEEE
// addition commutes, so both sides of a paired diagonal get bit-identical values.
TexCoord Mid(const TexCoord& a, const TexCoord& b) { return {(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5}; }

void RefineCorners(const std::vector<FaceTexCoords>& coarse, std::vector<FaceTexCoords>* fine) {
  fine->resize(coarse.size() * 4);
  for (size_t k = 0; k < coarse.size(); ++k) {
    const auto& [a, b, c] = coarse[k];
    const TexCoord ab = Mid(a, b), bc = Mid(b, c), ca = Mid(c, a);
    (*fine)[4 * k + 0] = {a, ab, ca};
    (*fine)[4 * k + 1] = {ab, b, bc};
    (*fine)[4 * k + 2] = {ca, bc, c};
    (*fine)[4 * k + 3] = {ab, bc, ca};
  }
}

uint64_t Bits(const std::array<float, 2>& uv) {
  uint32_t u = 0, v = 0;
  std::memcpy(&u, &uv[0], sizeof u);
  std::memcpy(&v, &uv[1], sizeof v);
  return (uint64_t{u} << 32) | v;
}

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// One welded vertex's copies, chained: the first is the vertex itself (an
// unreferenced vertex keeps its slot with coordinates (0, 0)); split copies are
// appended after the welded vertices.
class CopyTable {
 public:
  CopyTable(size_t vertices, SeamSplitMesh* out) : out_(out), seen_(vertices, false), keys_(vertices), next_(vertices, kNone) {
    out->source_vertex.resize(vertices);
    for (size_t v = 0; v < vertices; ++v) out->source_vertex[v] = static_cast<uint32_t>(v);
    out->texcoords.assign(vertices, {0.0f, 0.0f});
  }

  uint32_t CopyFor(uint32_t vertex, const std::array<float, 2>& uv) {
    const uint64_t key = Bits(uv);
    if (!seen_[vertex]) {
      seen_[vertex] = true;
      keys_[vertex] = key;
      out_->texcoords[vertex] = uv;
      return vertex;
    }
    uint32_t k = vertex;
    for (;; k = next_[k]) {
      if (keys_[k] == key) return k;
      if (next_[k] == kNone) break;
    }
    const uint32_t copy = static_cast<uint32_t>(out_->source_vertex.size());
    next_[k] = copy;
    out_->source_vertex.push_back(vertex);
    out_->texcoords.push_back(uv);
    keys_.push_back(key);
    next_.push_back(kNone);
    return copy;
  }

 private:
  SeamSplitMesh* out_;
  std::vector<bool> seen_;
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> next_;
};

}  // namespace

std::vector<FaceTexCoords> LevelCornerTexCoords(const SemiRegularMesh& mesh, int level,
                                                const std::vector<FaceTexCoords>& corners) {
  const std::vector<Face>& base = mesh.hierarchy.BaseFaces();
  std::vector<FaceTexCoords> out;
  out.reserve(mesh.hierarchy.Faces(level).size() + mesh.kept_exactly.faces.size());
  std::vector<FaceTexCoords> block, finer;
  for (size_t t = 0; t < base.size(); ++t) {
    block.assign(1, corners[t]);
    for (int j = 0; j < level; ++j) {
      RefineCorners(block, &finer);
      block.swap(finer);
    }
    out.insert(out.end(), block.begin(), block.end());
  }
  out.insert(out.end(), corners.begin() + static_cast<std::ptrdiff_t>(base.size()), corners.end());
  return out;
}

SeamSplitMesh SplitLevelAtSeams(const SemiRegularMesh& mesh, int level, const std::vector<FaceTexCoords>& corners) {
  const Mesh welded = ExtractLevel(mesh, level);
  const std::vector<FaceTexCoords> face_uvs = LevelCornerTexCoords(mesh, level, corners);
  SeamSplitMesh out;
  out.faces.resize(welded.faces.size());
  CopyTable copies(welded.positions.size(), &out);
  for (size_t f = 0; f < welded.faces.size(); ++f) {
    for (size_t k = 0; k < 3; ++k) {
      const std::array<float, 2> uv{static_cast<float>(face_uvs[f][k][0]), static_cast<float>(face_uvs[f][k][1])};
      out.faces[f][k] = copies.CopyFor(welded.faces[f][k], uv);
    }
  }
  return out;
}

}  // namespace eqmesh

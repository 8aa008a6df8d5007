#include "mesh_io/semi_regular_io.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "mesh_io/atomic_file.h"

namespace eqmesh {
namespace {

constexpr char kMagic[4] = {'E', 'Q', 'S', 'R'};
// Version 2 adds the crease edges; a mesh without them is written as version 1.
constexpr uint8_t kVersion = 1;
constexpr uint8_t kVersionCreases = 2;

bool HostIsLittleEndian() {
  const uint16_t probe = 1;
  uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

class Writer {
 public:
  template <typename T>
  void Put(T value) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &value, sizeof(T));
  }
  void PutMesh(const std::vector<Vec3>& positions, const std::vector<Face>& faces) {
    Put(static_cast<uint32_t>(positions.size()));
    Put(static_cast<uint32_t>(faces.size()));
    for (const Vec3& p : positions) {
      for (int i = 0; i < 3; ++i) Put(p[i]);
    }
    for (const Face& f : faces) {
      for (uint32_t v : f) Put(v);
    }
  }
  std::vector<char> bytes;
};

class Reader {
 public:
  Reader(const std::vector<char>& bytes, std::string name) : bytes_(bytes), name_(std::move(name)) {}

  template <typename T>
  Status Get(T* value) {
    if (bytes_.size() - offset_ < sizeof(T)) return Truncated();
    std::memcpy(value, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return Status::Ok();
  }
  // Checks that `count` records of `record_bytes` fit in what is left, before allocating.
  Status Require(uint64_t count, uint64_t record_bytes) const {
    if (count > (bytes_.size() - offset_) / record_bytes) return Truncated();
    return Status::Ok();
  }
  Status GetPositions(uint32_t count, std::vector<Vec3>* out) {
    EQMESH_RETURN_IF_ERROR(Require(count, 24));
    out->resize(count);
    for (Vec3& p : *out) {
      for (int i = 0; i < 3; ++i) {
        EQMESH_RETURN_IF_ERROR(Get(&p[i]));
        if (!std::isfinite(p[i])) return ParseError(name_ + ": non-finite coordinate");
      }
    }
    return Status::Ok();
  }
  Status GetFaces(uint32_t count, uint32_t num_vertices, std::vector<Face>* out) {
    EQMESH_RETURN_IF_ERROR(Require(count, 12));
    out->resize(count);
    for (Face& f : *out) {
      for (uint32_t& v : f) {
        EQMESH_RETURN_IF_ERROR(Get(&v));
        if (v >= num_vertices) return ParseError(name_ + ": face index out of range");
      }
    }
    return Status::Ok();
  }
  bool AtEnd() const { return offset_ == bytes_.size(); }
  Status Truncated() const { return ParseError(name_ + ": truncated semi-regular mesh file"); }

 private:
  const std::vector<char>& bytes_;
  std::string name_;
  size_t offset_ = 0;
};

Status ReadKinds(Reader* reader, uint32_t count, const std::string& path, std::vector<VertexKind>* kinds) {
  uint8_t has_kinds = 0;
  EQMESH_RETURN_IF_ERROR(reader->Get(&has_kinds));
  if (has_kinds > 1) return ParseError(path + ": bad kinds flag");
  if (!has_kinds) return Status::Ok();
  EQMESH_RETURN_IF_ERROR(reader->Require(count, 1));
  kinds->resize(count);
  for (VertexKind& k : *kinds) {
    uint8_t value = 0;
    EQMESH_RETURN_IF_ERROR(reader->Get(&value));
    if (value > static_cast<uint8_t>(VertexKind::kBoundary)) return ParseError(path + ": bad vertex kind");
    k = static_cast<VertexKind>(value);
  }
  return Status::Ok();
}

// Crease edges are edges of the base, which bounds their count.
Status ReadCreases(Reader* reader, const std::string& path, SemiRegularHierarchy* hierarchy) {
  uint32_t count = 0;
  EQMESH_RETURN_IF_ERROR(reader->Get(&count));
  if (count > 3 * hierarchy->BaseFaces().size()) return ParseError(path + ": more crease edges than base edges");
  std::vector<Edge> edges(count);
  for (Edge& e : edges) {
    EQMESH_RETURN_IF_ERROR(reader->Get(&e[0]));
    EQMESH_RETURN_IF_ERROR(reader->Get(&e[1]));
  }
  const Status set = hierarchy->SetBaseCreases(std::move(edges));
  if (!set.ok()) return ParseError(path + ": " + set.message());
  return Status::Ok();
}

}  // namespace

Status WriteSemiRegular(const SemiRegularMesh& mesh, const std::string& path) {
  if (!HostIsLittleEndian()) return UnsupportedFeature("semi-regular files need a little-endian host");
  const SemiRegularHierarchy& h = mesh.hierarchy;
  if (mesh.positions.size() != h.NumVertices(h.levels())) {
    return InvalidArgument(path + ": positions do not match the hierarchy");
  }
  Writer w;
  for (char c : kMagic) w.Put(c);
  w.Put(h.HasCreases() ? kVersionCreases : kVersion);
  w.Put(static_cast<uint8_t>(h.levels()));
  w.Put(uint16_t{0});
  w.Put(h.NumVertices(0));
  w.Put(static_cast<uint32_t>(h.BaseFaces().size()));
  for (const Face& f : h.BaseFaces()) {
    for (uint32_t v : f) w.Put(v);
  }
  w.Put(static_cast<uint32_t>(mesh.positions.size()));
  for (const Vec3& p : mesh.positions) {
    for (int i = 0; i < 3; ++i) w.Put(p[i]);
  }
  const bool has_kinds = mesh.kinds.size() == mesh.positions.size();
  w.Put(static_cast<uint8_t>(has_kinds));
  if (has_kinds) {
    for (VertexKind k : mesh.kinds) w.Put(static_cast<uint8_t>(k));
  }
  if (h.HasCreases()) {
    w.Put(static_cast<uint32_t>(h.BaseCreases().size()));
    for (const Edge& e : h.BaseCreases()) {
      w.Put(e[0]);
      w.Put(e[1]);
    }
  }
  w.PutMesh(mesh.kept_exactly.positions, mesh.kept_exactly.faces);
  return WriteFileAtomically(path, reinterpret_cast<const uint8_t*>(w.bytes.data()), w.bytes.size());
}

StatusOr<SemiRegularMesh> ReadSemiRegular(const std::string& path) {
  if (!HostIsLittleEndian()) return UnsupportedFeature("semi-regular files need a little-endian host");
  std::ifstream in(path, std::ios::binary);
  if (!in) return IoError(path + ": cannot open");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader r(bytes, path);
  char magic[4] = {};
  for (char& c : magic) EQMESH_RETURN_IF_ERROR(r.Get(&c));
  if (std::memcmp(magic, kMagic, 4) != 0) return ParseError(path + ": not a semi-regular mesh file");
  uint8_t version = 0, levels = 0;
  uint16_t reserved = 0;
  EQMESH_RETURN_IF_ERROR(r.Get(&version));
  EQMESH_RETURN_IF_ERROR(r.Get(&levels));
  EQMESH_RETURN_IF_ERROR(r.Get(&reserved));
  if (version != kVersion && version != kVersionCreases) return UnsupportedVersion(path + ": semi-regular file version " + std::to_string(version));
  uint32_t base_vertices = 0, base_faces = 0;
  EQMESH_RETURN_IF_ERROR(r.Get(&base_vertices));
  EQMESH_RETURN_IF_ERROR(r.Get(&base_faces));
  std::vector<Face> faces;
  EQMESH_RETURN_IF_ERROR(r.GetFaces(base_faces, base_vertices, &faces));
  // The file must hold every finest-level position (24 bytes each), which bounds
  // the hierarchy we agree to build.
  const uint64_t max_faces = std::max<uint64_t>(16, bytes.size() / 6);
  SemiRegularMesh mesh;
  EQMESH_ASSIGN_OR_RETURN(mesh.hierarchy, SemiRegularHierarchy::Build(base_vertices, std::move(faces), levels, max_faces));
  uint32_t vertex_count = 0;
  EQMESH_RETURN_IF_ERROR(r.Get(&vertex_count));
  if (vertex_count != mesh.hierarchy.NumVertices(levels)) {
    return ParseError(path + ": vertex count does not match the hierarchy");
  }
  EQMESH_RETURN_IF_ERROR(r.GetPositions(vertex_count, &mesh.positions));
  EQMESH_RETURN_IF_ERROR(ReadKinds(&r, vertex_count, path, &mesh.kinds));
  if (version == kVersionCreases) EQMESH_RETURN_IF_ERROR(ReadCreases(&r, path, &mesh.hierarchy));
  uint32_t kept_vertices = 0, kept_faces = 0;
  EQMESH_RETURN_IF_ERROR(r.Get(&kept_vertices));
  EQMESH_RETURN_IF_ERROR(r.Get(&kept_faces));
  EQMESH_RETURN_IF_ERROR(r.GetPositions(kept_vertices, &mesh.kept_exactly.positions));
  EQMESH_RETURN_IF_ERROR(r.GetFaces(kept_faces, kept_vertices, &mesh.kept_exactly.faces));
  if (!r.AtEnd()) return ParseError(path + ": trailing bytes after the semi-regular mesh");
  return mesh;
}

}  // namespace eqmesh

#include "fake_stream.h"

#include <cstring>
#include <string>

#include "mesh/semi_regular.h"

namespace eqmesh::testing {
namespace {

template <typename T>
void Put(std::vector<uint8_t>* out, T value) {
  uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->insert(out->end(), bytes, bytes + sizeof(T));
}

class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  template <typename T>
  Status Get(T* value) {
    if (size_ - pos_ < sizeof(T)) return CorruptStream("fake stream truncated at byte " + std::to_string(pos_));
    std::memcpy(value, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return Status::Ok();
  }
  size_t pos() const { return pos_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

uint64_t LevelChunkLength(int j) { return static_cast<uint64_t>(j) + 4; }

Status ReadBase(Reader* r, int* levels, Mesh* base) {
  char magic[4];
  for (char& c : magic) EQMESH_RETURN_IF_ERROR(r->Get(&c));
  if (std::memcmp(magic, "FAKE", 4) != 0) return CorruptStream("bad magic");
  uint8_t j = 0;
  uint32_t nv = 0, nf = 0;
  EQMESH_RETURN_IF_ERROR(r->Get(&j));
  EQMESH_RETURN_IF_ERROR(r->Get(&nv));
  EQMESH_RETURN_IF_ERROR(r->Get(&nf));
  if (j > 8 || nv > 100000 || nf > 100000) return CorruptStream("fake header out of range");
  *levels = j;
  base->positions.resize(nv);
  for (Vec3& p : base->positions)
    for (int i = 0; i < 3; ++i) EQMESH_RETURN_IF_ERROR(r->Get(&p[i]));
  base->faces.resize(nf);
  for (Face& f : base->faces)
    for (uint32_t& v : f) EQMESH_RETURN_IF_ERROR(r->Get(&v));
  return Status::Ok();
}

Status CheckLevelChunk(Reader* r, int j) {
  uint8_t tag = 0, level = 0;
  EQMESH_RETURN_IF_ERROR(r->Get(&tag));
  EQMESH_RETURN_IF_ERROR(r->Get(&level));
  if (tag != 'L' || level != j) return CorruptStream("level chunk " + std::to_string(j) + " has a bad tag");
  for (int i = 0; i < j + 2; ++i) {
    uint8_t pad = 0;
    EQMESH_RETURN_IF_ERROR(r->Get(&pad));
    if (pad != 0xAB) return CorruptStream("level chunk " + std::to_string(j) + " has a bad byte");
  }
  return Status::Ok();
}

}  // namespace

std::vector<uint8_t> MakeFakeStream(const Mesh& base, int levels) {
  std::vector<uint8_t> out = {'F', 'A', 'K', 'E', static_cast<uint8_t>(levels)};
  Put(&out, static_cast<uint32_t>(base.positions.size()));
  Put(&out, static_cast<uint32_t>(base.faces.size()));
  for (const Vec3& p : base.positions)
    for (int i = 0; i < 3; ++i) Put(&out, p[i]);
  for (const Face& f : base.faces)
    for (uint32_t v : f) Put(&out, v);
  for (int j = 1; j <= levels; ++j) {
    out.push_back('L');
    out.push_back(static_cast<uint8_t>(j));
    out.insert(out.end(), static_cast<size_t>(j) + 2, 0xAB);
  }
  return out;
}

StatusOr<gltf::DecodedStream> DecodeFakeStream(const uint8_t* data, size_t size, int max_level, uint64_t) {
  Reader r(data, size);
  gltf::DecodedStream out;
  Mesh base;
  EQMESH_RETURN_IF_ERROR(ReadBase(&r, &out.stream_levels, &base));
  out.chunk_lengths.push_back(r.pos());
  for (int j = 1; j <= out.stream_levels; ++j) out.chunk_lengths.push_back(LevelChunkLength(j));
  out.level_decoded = max_level < 0 ? out.stream_levels : std::min(max_level, out.stream_levels);
  for (int j = 1; j <= out.level_decoded; ++j) EQMESH_RETURN_IF_ERROR(CheckLevelChunk(&r, j));
  if (max_level < 0 && r.pos() != size) return CorruptStream("trailing bytes after the last level");
  EQMESH_ASSIGN_OR_RETURN(SemiRegularHierarchy h,
                          SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()), base.faces,
                                                      out.level_decoded));
  std::vector<Vec3> positions = base.positions;
  for (int j = 0; j < out.level_decoded; ++j) {
    for (const Edge& e : h.OddEdges(j)) positions.push_back(0.5 * (positions[e[0]] + positions[e[1]]));
  }
  out.mesh.positions = std::move(positions);
  out.mesh.faces = h.Faces(out.level_decoded);
  return out;
}

gltf::GeometryCompressor FakeCompressor(int levels) {
  return [levels](const gltf::PrimitiveGeometry& primitive, const std::string&) -> StatusOr<gltf::CompressedGeometry> {
    gltf::CompressedGeometry out;
    out.stream = MakeFakeStream(primitive.mesh, levels);
    EQMESH_ASSIGN_OR_RETURN(gltf::DecodedStream decoded, DecodeFakeStream(out.stream.data(), out.stream.size(), -1));
    out.chunk_lengths = decoded.chunk_lengths;
    out.decoded = std::move(decoded.mesh);
    return out;
  };
}

}  // namespace eqmesh::testing

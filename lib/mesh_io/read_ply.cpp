// PLY (Turk 1994) in all three encodings. Only three things are read: the x, y, z
// scalars of `vertex`, the index list of `face` (fan-triangulated) and the index
// list of `tristrips` (-1 restarts a strip); every other property and element is
// read past by its declared type. One templated body walker serves the ascii and
// binary encodings, so both accept exactly the same files.
#include <cmath>
#include <cstring>
#include <limits>

#include "mesh_io/mesh_reader_support.h"
#include "mesh_io/ply_header_reader.h"

namespace eqmesh::io_internal {
namespace {

constexpr bool kHostIsBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;

template <typename T>
T LoadScalar(const uint8_t* p, bool swap) {
  uint8_t raw[sizeof(T)];
  std::memcpy(raw, p, sizeof(T));
  if (swap) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  T v;
  std::memcpy(&v, raw, sizeof(T));
  return v;
}

double LoadAsDouble(PlyType type, const uint8_t* p, bool swap) {
  switch (type) {
    case PlyType::kInt8: return LoadScalar<int8_t>(p, swap);
    case PlyType::kUInt8: return LoadScalar<uint8_t>(p, swap);
    case PlyType::kInt16: return LoadScalar<int16_t>(p, swap);
    case PlyType::kUInt16: return LoadScalar<uint16_t>(p, swap);
    case PlyType::kInt32: return LoadScalar<int32_t>(p, swap);
    case PlyType::kUInt32: return LoadScalar<uint32_t>(p, swap);
    case PlyType::kFloat32: return LoadScalar<float>(p, swap);
    case PlyType::kFloat64: return LoadScalar<double>(p, swap);
  }
  return 0.0;
}

// Converts a value meant as an index or count; false unless it is an exact integer.
bool AsInteger(double v, int64_t* out) {
  if (!(v >= -9.0e15 && v <= 9.0e15) || v != std::floor(v)) return false;
  *out = static_cast<int64_t>(v);
  return true;
}

class BinarySource {
 public:
  BinarySource(const uint8_t* begin, const uint8_t* body, const uint8_t* end, bool big_endian)
      : begin_(begin), p_(body), end_(end), swap_(big_endian != kHostIsBigEndian) {}

  bool ReadDouble(PlyType type, double* out) {
    const size_t n = PlyTypeSize(type);
    if (static_cast<size_t>(end_ - p_) < n) return false;
    *out = LoadAsDouble(type, p_, swap_);
    p_ += n;
    return true;
  }
  bool ReadInteger(PlyType type, int64_t* out) {
    double v = 0;
    return ReadDouble(type, &v) && AsInteger(v, out);
  }
  bool Skip(PlyType type, uint64_t count) {
    const size_t n = PlyTypeSize(type);
    if (count > static_cast<uint64_t>(end_ - p_) / n) return false;
    p_ += count * n;
    return true;
  }
  std::string Where() const { return "byte " + std::to_string(p_ - begin_); }
  std::string Problem() const {
    return p_ == end_ ? "binary data truncated (file ends at byte " + std::to_string(end_ - begin_) + ")"
                      : "bad binary value";
  }

 private:
  const uint8_t* begin_;
  const uint8_t* p_;
  const uint8_t* end_;
  bool swap_;
};

class AsciiSource {
 public:
  AsciiSource(const uint8_t* body, const uint8_t* end, size_t first_line)
      : p_(reinterpret_cast<const char*>(body)), end_(reinterpret_cast<const char*>(end)), line_(first_line) {}

  bool ReadDouble(PlyType /*type*/, double* out) {
    NextToken();
    const char* next = ParseDouble(p_, end_, out);
    return Accept(next);
  }
  bool ReadInteger(PlyType /*type*/, int64_t* out) {
    NextToken();
    const char* next = ParseInt64(p_, end_, out);
    return Accept(next);
  }
  bool Skip(PlyType /*type*/, uint64_t count) {
    for (uint64_t i = 0; i < count; ++i) {
      NextToken();
      if (p_ == end_) return false;
      p_ = SkipToken(p_, end_);
    }
    return true;
  }
  std::string Where() const { return "line " + std::to_string(line_); }
  std::string Problem() const {
    return p_ == end_ ? "file ends early" : "bad number " + TokenForError(p_, end_);
  }

 private:
  void NextToken() {
    while (p_ < end_ && IsSpace(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
  }
  bool Accept(const char* next) {
    if (next == nullptr || (next < end_ && !IsSpace(*next))) return false;
    p_ = next;
    return true;
  }

  const char* p_;
  const char* end_;
  size_t line_;
};

enum class Role { kVertex, kFace, kTriStrips, kOther };

Role RoleOf(const PlyElement& e) {
  if (e.name == "vertex") return Role::kVertex;
  if (e.name == "face") return Role::kFace;
  if (e.name == "tristrips") return Role::kTriStrips;
  return Role::kOther;
}

int FindProperty(const PlyElement& e, const char* name) {
  for (size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i].name == name) return static_cast<int>(i);
  return -1;
}

template <class Source>
class PlyBodyReader {
 public:
  PlyBodyReader(Source* src, const std::string& name, MeshBuilder* builder)
      : src_(src), name_(name), builder_(builder) {}

  Status ReadElement(const PlyElement& e) {
    const Role role = RoleOf(e);
    EQMESH_RETURN_IF_ERROR(FindSlots(e, role));
    if (role == Role::kVertex) builder_->mesh().positions.reserve(builder_->num_positions() + e.count);
    for (uint64_t i = 0; i < e.count; ++i) {
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& prop = e.properties[k];
        if (prop.is_list) EQMESH_RETURN_IF_ERROR(ReadList(prop, static_cast<int>(k) == list_slot_));
        else ReadScalar(prop, k);
        if (!ok_) return Fail(e, i);
      }
      if (role == Role::kVertex) builder_->AddPosition(xyz_[0], xyz_[1], xyz_[2]);
      if (role == Role::kFace || role == Role::kTriStrips) EQMESH_RETURN_IF_ERROR(EmitFaces(role));
    }
    if (role == Role::kVertex) vertices_known_ = true;
    return Status::Ok();
  }

 private:
  Status FindSlots(const PlyElement& e, Role role) {
    xyz_slot_[0] = xyz_slot_[1] = xyz_slot_[2] = -1;
    list_slot_ = -1;
    if (role == Role::kVertex) {
      const char* axes[3] = {"x", "y", "z"};
      for (int a = 0; a < 3; ++a) {
        xyz_slot_[a] = FindProperty(e, axes[a]);
        if (xyz_slot_[a] < 0 || e.properties[xyz_slot_[a]].is_list) {
          return ParseError(name_ + ": vertex element has no scalar property '" + axes[a] + "'");
        }
      }
    } else if (role != Role::kOther) {
      list_slot_ = FindProperty(e, "vertex_indices");
      if (list_slot_ < 0) list_slot_ = FindProperty(e, "vertex_index");
      if (list_slot_ < 0 || !e.properties[list_slot_].is_list) {
        return ParseError(name_ + ": " + e.name + " element has no vertex_indices list");
      }
    }
    return Status::Ok();
  }

  void ReadScalar(const PlyProperty& prop, size_t k) {
    for (int a = 0; a < 3; ++a) {
      if (xyz_slot_[a] == static_cast<int>(k)) {
        ok_ = src_->ReadDouble(prop.type, &xyz_[a]);
        return;
      }
    }
    ok_ = src_->Skip(prop.type, 1);
  }

  Status ReadList(const PlyProperty& prop, bool keep) {
    int64_t n = 0;
    ok_ = src_->ReadInteger(prop.count_type, &n);
    if (!ok_) return Status::Ok();
    if (n < 0) return ParseError(name_ + ": " + src_->Where() + ": negative list length " + std::to_string(n));
    if (!keep) {
      ok_ = src_->Skip(prop.type, static_cast<uint64_t>(n));
      return Status::Ok();
    }
    indices_.clear();
    for (int64_t j = 0; j < n && ok_; ++j) {
      int64_t idx = 0;
      ok_ = src_->ReadInteger(prop.type, &idx);
      indices_.push_back(idx);
    }
    return Status::Ok();
  }

  Status Fail(const PlyElement& e, uint64_t i) const {
    return ParseError(name_ + ": " + src_->Where() + ": " + src_->Problem() + " in element '" + e.name + "' " +
                      std::to_string(i) + " of " + std::to_string(e.count));
  }

  // Validates an index from the file; -1 passes only where it restarts a strip.
  Status CheckIndex(int64_t idx) const {
    const uint64_t limit = vertices_known_ ? builder_->num_positions() : std::numeric_limits<uint32_t>::max();
    if (idx >= 0 && static_cast<uint64_t>(idx) < limit) return Status::Ok();
    return ParseError(name_ + ": " + src_->Where() + ": face index " + std::to_string(idx) + " out of range (" +
                      std::to_string(builder_->num_positions()) + " vertices)");
  }

  Status EmitFaces(Role role) {
    corners_.clear();
    for (int64_t idx : indices_) {
      if (role == Role::kTriStrips && idx == -1) {
        EmitStrip();
        corners_.clear();
        continue;
      }
      EQMESH_RETURN_IF_ERROR(CheckIndex(idx));
      corners_.push_back(static_cast<uint32_t>(idx));
    }
    if (role == Role::kTriStrips) EmitStrip();
    else builder_->AddPolygon(corners_.data(), corners_.size());
    return Status::Ok();
  }

  // Strip triangle k is (s[k], s[k+1], s[k+2]) for even k and (s[k+1], s[k], s[k+2])
  // for odd k, which keeps one orientation; triangles with a repeated corner are the
  // strip's stitching, not geometry.
  void EmitStrip() {
    for (size_t k = 0; k + 2 < corners_.size(); ++k) {
      uint32_t a = corners_[k], b = corners_[k + 1];
      const uint32_t c = corners_[k + 2];
      if (k % 2 == 1) std::swap(a, b);
      if (a == b || b == c || a == c) continue;
      builder_->AddTriangle(a, b, c);
    }
  }

  Source* src_;
  const std::string& name_;
  MeshBuilder* builder_;
  bool vertices_known_ = false;
  bool ok_ = true;
  int xyz_slot_[3] = {-1, -1, -1};
  int list_slot_ = -1;
  double xyz_[3] = {0, 0, 0};
  std::vector<int64_t> indices_;
  std::vector<uint32_t> corners_;
};

template <class Source>
Status ReadBody(const PlyHeader& header, Source* src, const std::string& name, MeshBuilder* builder) {
  PlyBodyReader<Source> reader(src, name, builder);
  for (const PlyElement& e : header.elements) EQMESH_RETURN_IF_ERROR(reader.ReadElement(e));
  return Status::Ok();
}

size_t CountLines(const uint8_t* data, size_t size) {
  size_t lines = 0;
  for (size_t i = 0; i < size; ++i) lines += data[i] == '\n';
  return lines;
}

}  // namespace

StatusOr<Mesh> ReadPly(const uint8_t* data, size_t size, const std::string& name, ReadReport* report) {
  report->format = "ply";
  EQMESH_ASSIGN_OR_RETURN(const PlyHeader header, ParsePlyHeader(data, size, name));
  const size_t body_bytes = size - header.body_offset;
  EQMESH_RETURN_IF_ERROR(CheckPlyCountsFitBody(header, body_bytes, name));
  report->notes.push_back(std::string("ply format ") + PlyFormatName(header.format));
  MeshBuilder builder;
  const uint8_t* body = data + header.body_offset;
  if (header.format == PlyFormat::kAscii) {
    AsciiSource src(body, data + size, CountLines(data, header.body_offset) + 1);
    EQMESH_RETURN_IF_ERROR(ReadBody(header, &src, name, &builder));
  } else {
    BinarySource src(data, body, data + size, header.format == PlyFormat::kBinaryBigEndian);
    EQMESH_RETURN_IF_ERROR(ReadBody(header, &src, name, &builder));
  }
  return FinishMesh(std::move(builder), name, report);
}

}  // namespace eqmesh::io_internal

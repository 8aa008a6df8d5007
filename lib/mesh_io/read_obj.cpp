// Wavefront OBJ: only `v` and `f` matter to a geometry codec. Texture/normal
// references in face corners ("1/2/3", "1//3") are read past, relative (negative)
// indices resolve against the vertices seen so far, as the format defines.
#include <cmath>
#include <cstring>
#include <limits>

#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::io_internal {
namespace {

struct ObjState {
  const std::string& name;
  MeshBuilder builder;
  std::vector<uint32_t> corners;
  int64_t max_index = -1;  // largest absolute index, checked once all `v` are known
  size_t max_index_line = 0;
};

Status ParseVertex(const char* p, const char* end, size_t line, ObjState* s) {
  double xyz[3];
  for (double& c : xyz) {
    p = SkipBlanks(p, end);
    const char* next = ParseDouble(p, end, &c);
    if (next == nullptr || (next < end && !IsBlank(*next))) {
      return ParseErrorAt(s->name, line, "bad vertex coordinate " + TokenForError(p, end));
    }
    p = next;
  }
  if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
    return Status(StatusCode::kInvalidMesh,
                  s->name + ": line " + std::to_string(line) + ": vertex " + std::to_string(s->builder.num_positions()) +
                      " (0-based) has a non-finite coordinate (" + FormatCoordinate(xyz[0]) + ", " +
                      FormatCoordinate(xyz[1]) + ", " + FormatCoordinate(xyz[2]) + ")");
  }
  s->builder.AddPosition(xyz[0], xyz[1], xyz[2]);  // a 4th (w) or colour values are ignored
  return Status::Ok();
}

Status ResolveIndex(int64_t idx, const char* token, const char* end, size_t line, ObjState* s,
                    uint32_t* out) {
  const int64_t seen = static_cast<int64_t>(s->builder.num_positions());
  if (idx < 0) {
    if (idx < -seen) {  // not -idx > seen: -INT64_MIN overflows
      return ParseErrorAt(s->name, line, "relative face index " + std::to_string(idx) + " out of range (" +
                                             std::to_string(seen) + " vertices so far)");
    }
    *out = static_cast<uint32_t>(seen + idx);
    return Status::Ok();
  }
  if (idx == 0 || idx > int64_t{std::numeric_limits<uint32_t>::max()}) {
    return ParseErrorAt(s->name, line, "bad face index " + TokenForError(token, end));
  }
  if (idx > s->max_index) {
    s->max_index = idx;
    s->max_index_line = line;
  }
  *out = static_cast<uint32_t>(idx - 1);
  return Status::Ok();
}

Status ParseFace(const char* p, const char* end, size_t line, ObjState* s) {
  s->corners.clear();
  while ((p = SkipBlanks(p, end)) < end) {
    int64_t idx = 0;
    const char* next = ParseInt64(p, end, &idx);
    if (next == nullptr || (next < end && !IsBlank(*next) && *next != '/')) {
      return ParseErrorAt(s->name, line, "bad face index " + TokenForError(p, end));
    }
    uint32_t resolved = 0;
    EQMESH_RETURN_IF_ERROR(ResolveIndex(idx, p, end, line, s, &resolved));
    s->corners.push_back(resolved);
    p = SkipToken(next, end);
  }
  s->builder.AddPolygon(s->corners.data(), s->corners.size());
  return Status::Ok();
}

// Dispatches one line; keywords other than v and f (vt, vn, g, usemtl, l, ...) are ignored.
Status ParseLine(const char* p, const char* end, size_t line, ObjState* s) {
  p = SkipBlanks(p, end);
  if (end - p < 2 || !IsBlank(p[1])) return Status::Ok();
  if (p[0] == 'v') return ParseVertex(p + 2, end, line, s);
  if (p[0] == 'f') return ParseFace(p + 2, end, line, s);
  return Status::Ok();
}

}  // namespace

StatusOr<Mesh> ReadObj(const uint8_t* data, size_t size, const std::string& name, ReadReport* report) {
  report->format = "obj";
  if (size == 0) return ParseError(name + ": empty file");
  if (const void* nul = std::memchr(data, 0, size)) {
    return ParseError(name + ": binary data (NUL byte at offset " +
                      std::to_string(static_cast<const uint8_t*>(nul) - data) + "), not a text OBJ file");
  }
  ObjState s{name, {}, {}, -1, 0};
  const char* p = reinterpret_cast<const char*>(data);
  const char* const end = p + size;
  size_t line = 0;
  while (p < end) {
    ++line;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<size_t>(end - p)));
    if (eol == nullptr) eol = end;
    EQMESH_RETURN_IF_ERROR(ParseLine(p, eol, line, &s));
    p = eol + (eol < end ? 1 : 0);
  }
  const int64_t n = static_cast<int64_t>(s.builder.num_positions());
  if (s.max_index > n) {
    return ParseErrorAt(name, s.max_index_line, "face index " + std::to_string(s.max_index) + " out of range (" +
                                                    std::to_string(n) + " vertices)");
  }
  if (s.builder.mesh().faces.empty() && n == 0) {
    return ParseError(name + ": no 'v' or 'f' lines, not an OBJ file");
  }
  return FinishMesh(std::move(s.builder), name, report);
}

}  // namespace eqmesh::io_internal

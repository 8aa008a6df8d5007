// Object File Format (Geomview): a keyword, "V F E" counts, V vertex lines and F
// face lines "n i0 .. in-1 [colour]". The prefixes C/N/ST only append values to the
// vertex lines, which are ignored; 4OFF and nOFF change the dimension and are not
// supported. Parsing is line based: '#' starts a comment, blank lines are skipped.
#include <cstring>

#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::io_internal {
namespace {

// Fewest bytes a vertex line ("0 0 0\n") and a face line ("0\n", skipped) can take.
constexpr uint64_t kMinVertexBytes = 6;
constexpr uint64_t kMinFaceBytes = 2;

class OffLines {
 public:
  OffLines(const uint8_t* data, size_t size)
      : p_(reinterpret_cast<const char*>(data)), end_(p_ + size) {}

  // Next line with content (comments stripped); false at end of file.
  bool Next(const char** begin, const char** end) {
    while (p_ < end_) {
      ++line_;
      const char* eol = static_cast<const char*>(std::memchr(p_, '\n', static_cast<size_t>(end_ - p_)));
      if (eol == nullptr) eol = end_;
      const char* hash = static_cast<const char*>(std::memchr(p_, '#', static_cast<size_t>(eol - p_)));
      const char* e = hash ? hash : eol;
      const char* b = SkipBlanks(p_, e);
      p_ = eol + (eol < end_ ? 1 : 0);
      if (b == e) continue;
      *begin = b;
      *end = e;
      return true;
    }
    return false;
  }
  size_t line() const { return line_; }
  size_t remaining() const { return static_cast<size_t>(end_ - p_); }

 private:
  const char* p_;
  const char* end_;
  size_t line_ = 0;
};

// Accepts [ST][C][N]OFF; returns false for anything else.
bool IsOffKeyword(const char* b, const char* e, std::string* unsupported) {
  const std::string word(b, e);
  if (word.size() < 3 || word.compare(word.size() - 3, 3, "OFF") != 0) return false;
  const std::string prefix = word.substr(0, word.size() - 3);
  if (prefix.find('4') != std::string::npos || prefix.find('n') != std::string::npos) *unsupported = word;
  return prefix.find_first_not_of("STCN4n") == std::string::npos;
}

Status ReadCounts(OffLines* lines, const std::string& name, uint64_t counts[3]) {
  const char* b = nullptr;
  const char* e = nullptr;
  if (!lines->Next(&b, &e)) return ParseError(name + ": empty file");
  const char* word_end = SkipToken(b, e);
  std::string unsupported;
  if (IsOffKeyword(b, word_end, &unsupported)) {
    if (!unsupported.empty()) return UnsupportedFeature(name + ": OFF variant '" + unsupported + "' not supported");
    b = SkipBlanks(word_end, e);
    if (b == e && !lines->Next(&b, &e)) return ParseError(name + ": OFF header without counts");
  }
  for (int i = 0; i < 2; ++i) {  // the edge count is optional and unused
    b = SkipBlanks(b, e);
    int64_t v = 0;
    const char* next = ParseInt64(b, e, &v);
    if (next == nullptr || v < 0) return ParseErrorAt(name, lines->line(), "bad OFF count " + TokenForError(b, e));
    counts[i] = static_cast<uint64_t>(v);
    b = next;
  }
  return Status::Ok();
}

Status ReadVertices(OffLines* lines, uint64_t count, const std::string& name, MeshBuilder* builder) {
  builder->mesh().positions.reserve(count);
  for (uint64_t v = 0; v < count; ++v) {
    const char* b = nullptr;
    const char* e = nullptr;
    if (!lines->Next(&b, &e)) return ParseError(name + ": file ends after " + std::to_string(v) + " of " + std::to_string(count) + " vertices");
    double xyz[3];
    for (double& c : xyz) {
      b = SkipBlanks(b, e);
      const char* next = ParseDouble(b, e, &c);
      if (next == nullptr || (next < e && !IsBlank(*next))) {
        return ParseErrorAt(name, lines->line(), "bad vertex coordinate " + TokenForError(b, e));
      }
      b = next;
    }
    builder->AddPosition(xyz[0], xyz[1], xyz[2]);
  }
  return Status::Ok();
}

Status ReadFaces(OffLines* lines, uint64_t count, const std::string& name, MeshBuilder* builder) {
  const uint64_t num_vertices = builder->num_positions();
  std::vector<uint32_t> corners;
  for (uint64_t f = 0; f < count; ++f) {
    const char* b = nullptr;
    const char* e = nullptr;
    if (!lines->Next(&b, &e)) return ParseError(name + ": file ends after " + std::to_string(f) + " of " + std::to_string(count) + " faces");
    int64_t n = 0;
    b = ParseInt64(b, e, &n);
    // Each corner needs at least two characters, which bounds n by the line length.
    if (b == nullptr || n < 0 || n > (e - b)) return ParseErrorAt(name, lines->line(), "bad face vertex count");
    corners.clear();
    for (int64_t k = 0; k < n; ++k) {
      b = SkipBlanks(b, e);
      int64_t idx = 0;
      const char* next = ParseInt64(b, e, &idx);
      if (next == nullptr || (next < e && !IsBlank(*next))) return ParseErrorAt(name, lines->line(), "bad face index " + TokenForError(b, e));
      if (idx < 0 || static_cast<uint64_t>(idx) >= num_vertices) {
        return ParseErrorAt(name, lines->line(), "face index " + std::to_string(idx) + " out of range (" +
                                                     std::to_string(num_vertices) + " vertices)");
      }
      corners.push_back(static_cast<uint32_t>(idx));
      b = next;
    }
    builder->AddPolygon(corners.data(), corners.size());  // trailing colour values ignored
  }
  return Status::Ok();
}

}  // namespace

StatusOr<Mesh> ReadOff(const uint8_t* data, size_t size, const std::string& name, ReadReport* report) {
  report->format = "off";
  if (size == 0) return ParseError(name + ": empty file");
  if (std::memchr(data, 0, size) != nullptr) return ParseError(name + ": binary data, not a text OFF file");
  OffLines lines(data, size);
  uint64_t counts[3] = {0, 0, 0};
  EQMESH_RETURN_IF_ERROR(ReadCounts(&lines, name, counts));
  const uint64_t room = lines.remaining() + 1;  // the last line may lack its newline
  if (counts[0] > room / kMinVertexBytes || counts[1] > room / kMinFaceBytes ||
      counts[0] * kMinVertexBytes + counts[1] * kMinFaceBytes > room) {
    return ParseError(name + ": header declares " + std::to_string(counts[0]) + " vertices and " +
                      std::to_string(counts[1]) + " faces, more than the " + std::to_string(lines.remaining()) +
                      " remaining bytes can hold");
  }
  MeshBuilder builder;
  EQMESH_RETURN_IF_ERROR(ReadVertices(&lines, counts[0], name, &builder));
  EQMESH_RETURN_IF_ERROR(ReadFaces(&lines, counts[1], name, &builder));
  return FinishMesh(std::move(builder), name, report);
}

}  // namespace eqmesh::io_internal

// Internal to the mesh readers: the builder every format parser fills, the step that
// turns it into the readers' normal form (see mesh_io.h), number parsing on raw
// buffers, and the per-format entry points ReadMeshFromBytes dispatches to.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh::io_internal {

// Vertices and triangles as a parser finds them, before validation.
class MeshBuilder {
 public:
  void AddPosition(double x, double y, double z) { mesh_.positions.emplace_back(x, y, z); }
  // Fan-triangulates; polygons with fewer than three corners are counted, not kept.
  void AddPolygon(const uint32_t* corners, size_t n);
  void AddTriangle(uint32_t a, uint32_t b, uint32_t c) { mesh_.faces.push_back({a, b, c}); }
  size_t num_positions() const { return mesh_.positions.size(); }
  Mesh& mesh() { return mesh_; }
  size_t polygons_triangulated() const { return polygons_triangulated_; }
  size_t short_polygons_skipped() const { return short_polygons_skipped_; }

 private:
  Mesh mesh_;
  size_t polygons_triangulated_ = 0;
  size_t short_polygons_skipped_ = 0;
};

// Checks coordinates and indices, drops unreferenced vertices and fills the report's
// counters. Errors are prefixed with `name`.
StatusOr<Mesh> FinishMesh(MeshBuilder&& builder, const std::string& name, ReadReport* report);

// "name: line 12: message" as a parse error.
Status ParseErrorAt(const std::string& name, size_t line, const std::string& message);

inline bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
inline bool IsSpace(char c) { return IsBlank(c) || c == '\n'; }

inline const char* SkipBlanks(const char* p, const char* end) {
  while (p < end && IsBlank(*p)) ++p;
  return p;
}

inline const char* SkipToken(const char* p, const char* end) {
  while (p < end && !IsSpace(*p)) ++p;
  return p;
}

// Parses a decimal double at p (a leading '+' is allowed, "nan"/"inf" parse and are
// rejected later by FinishMesh). Returns the end of the number or nullptr.
inline const char* ParseDouble(const char* p, const char* end, double* out) {
  if (p < end && *p == '+') ++p;
  const std::from_chars_result r = std::from_chars(p, end, *out);
  return r.ec == std::errc() ? r.ptr : nullptr;
}

inline const char* ParseInt64(const char* p, const char* end, int64_t* out) {
  if (p < end && *p == '+') ++p;
  const std::from_chars_result r = std::from_chars(p, end, *out);
  return r.ec == std::errc() ? r.ptr : nullptr;
}

// A coordinate for error messages: "nan", "inf", "-inf" or its decimal value.
std::string FormatCoordinate(double v);

// The token starting at p, for error messages (at most 32 characters).
std::string TokenForError(const char* p, const char* end);

// tinygltf 2.7 (Debian bookworm) checks a GLB chunk's length without its 8-byte
// chunk header and then reads up to 8 bytes past the caller's buffer; every GLB goes
// through this check first. Fails when a chunk extends past the end of the file
// (the GLB header's length or the buffer, whichever is shorter).
Status CheckGlbChunkLengths(const uint8_t* data, size_t size, const std::string& name);

// Per-format parsers over the whole (already inflated) file.
StatusOr<Mesh> ReadObj(const uint8_t* data, size_t size, const std::string& name, ReadReport* report);
StatusOr<Mesh> ReadPly(const uint8_t* data, size_t size, const std::string& name, ReadReport* report);
StatusOr<Mesh> ReadOff(const uint8_t* data, size_t size, const std::string& name, ReadReport* report);
// `binary` selects GLB over JSON glTF; `base_dir` resolves external URIs.
StatusOr<Mesh> ReadGltf(const uint8_t* data, size_t size, bool binary, const std::string& name,
                        const std::string& base_dir, ReadReport* report);

}  // namespace eqmesh::io_internal

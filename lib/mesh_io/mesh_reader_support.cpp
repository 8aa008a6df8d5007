#include "mesh_io/mesh_reader_support.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace eqmesh::io_internal {

std::string FormatCoordinate(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return std::to_string(v);
}

namespace {

Status CheckFinite(const Mesh& mesh, const std::string& name) {
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3& p = mesh.positions[v];
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())) continue;
    return InvalidMesh(name + ": vertex " + std::to_string(v) + " (0-based, as stored) has a non-finite coordinate (" +
                       FormatCoordinate(p.x()) + ", " + FormatCoordinate(p.y()) + ", " +
                       FormatCoordinate(p.z()) + ")");
  }
  return Status::Ok();
}

// Parsers check indices where they know the vertex count; this catches the rest
// (faces stored before vertices, OBJ forward references).
Status CheckIndices(const Mesh& mesh, const std::string& name) {
  const size_t n = mesh.positions.size();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t i : mesh.faces[f]) {
      if (i < n) continue;
      return ParseError(name + ": triangle " + std::to_string(f) + ": vertex index " + std::to_string(i) +
                        " out of range (" + std::to_string(n) + " vertices)");
    }
  }
  return Status::Ok();
}

}  // namespace

void MeshBuilder::AddPolygon(const uint32_t* corners, size_t n) {
  if (n < 3) {
    ++short_polygons_skipped_;
    return;
  }
  if (n > 3) ++polygons_triangulated_;
  for (size_t i = 1; i + 1 < n; ++i) mesh_.faces.push_back({corners[0], corners[i], corners[i + 1]});
}

StatusOr<Mesh> FinishMesh(MeshBuilder&& builder, const std::string& name, ReadReport* report) {
  Mesh mesh = std::move(builder.mesh());
  if (mesh.positions.size() > std::numeric_limits<uint32_t>::max()) {
    return ResourceLimit(name + ": more than 2^32-1 vertices");
  }
  EQMESH_RETURN_IF_ERROR(CheckFinite(mesh, name));
  EQMESH_RETURN_IF_ERROR(CheckIndices(mesh, name));
  if (mesh.faces.empty()) {
    return InvalidMesh(name + ": no faces (" + std::to_string(mesh.positions.size()) + " vertices)");
  }
  report->dropped_unreferenced_vertices = DropUnreferencedVertices(&mesh);
  report->polygons_triangulated = builder.polygons_triangulated();
  if (builder.short_polygons_skipped() > 0) {
    report->notes.push_back(std::to_string(builder.short_polygons_skipped()) +
                            " faces with fewer than 3 vertices skipped");
  }
  return mesh;
}

Status CheckGlbChunkLengths(const uint8_t* data, size_t size, const std::string& name) {
  auto u32 = [data](uint64_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(data[at + static_cast<uint64_t>(i)]) << (8 * i);
    return v;
  };
  if (size < 12) return Status::Ok();  // tinygltf rejects it
  const uint64_t end = std::min<uint64_t>(u32(8), size);
  for (uint64_t offset = 12; offset + 8 <= end;) {
    const uint64_t chunk_end = offset + 8 + u32(offset);
    if (chunk_end > end) {
      return ParseError(name + ": GLB chunk at byte " + std::to_string(offset) + " extends past the end of the file");
    }
    offset = chunk_end;
  }
  return Status::Ok();
}

Status ParseErrorAt(const std::string& name, size_t line, const std::string& message) {
  return ParseError(name + ": line " + std::to_string(line) + ": " + message);
}

std::string TokenForError(const char* p, const char* end) {
  const char* e = SkipToken(p, end);
  if (e == p) return "end of line";
  std::string token(p, static_cast<size_t>(std::min<ptrdiff_t>(e - p, 32)));
  for (char& c : token)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "'" + token + "'";
}

}  // namespace eqmesh::io_internal

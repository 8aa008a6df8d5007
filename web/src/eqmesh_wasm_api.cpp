// The C API of the WebAssembly decoder (web/EqmeshDecoder.js is its only caller):
// stream bytes and a finest level in; float32 positions, unit normals, TEXCOORD_0
// (streams with an atlas, split at its seams as the native loader does) and uint32
// indices out, or an eqmesh StatusCode with its message. A result is one heap
// object the caller reads through accessors and frees, so no C++ type crosses
// the boundary and the JS side can copy the arrays straight out of the heap.
#include <emscripten.h>

#include <cstdint>
#include <string>
#include <vector>

#include "coding/decoded_geometry.h"
#include "coding/decoder.h"
#include "mesh/mesh.h"

namespace {

struct EqmResult {
  int status = 0;  // eqmesh::StatusCode
  std::string message;
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<float> texcoords;  // empty without an atlas
  std::vector<uint32_t> indices;
  int levels_in_stream = 0;
  int level_decoded = 0;
  int coder = 0;
  std::vector<double> chunk_lengths;  // doubles: JS numbers hold them exactly
};

EqmResult* Failure(const eqmesh::Status& status) {
  auto* r = new EqmResult;
  r->status = static_cast<int>(status.code());
  r->message = status.message();
  return r;
}

// What levelByteRanges must restate (ext_spec rule 11): range 0 covers header,
// base and kept chunks, then one range per level chunk.
void SetLayout(const eqmesh::StreamInfo& s, EqmResult* r) {
  r->levels_in_stream = s.levels;
  r->coder = static_cast<int>(s.coder);
  r->chunk_lengths.assign(1, static_cast<double>(s.header_size + s.base_size + s.kept_size + s.atlas_size + s.crease_size));
  for (uint64_t size : s.level_sizes) r->chunk_lengths.push_back(static_cast<double>(size));
}

void SetGeometry(const eqmesh::DecodedGeometry& g, EqmResult* r) {
  const size_t n = g.mesh.positions.size();
  r->positions.resize(n * 3);
  r->normals.resize(n * 3);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      r->positions[3 * i + c] = static_cast<float>(g.mesh.positions[i][c]);
      r->normals[3 * i + c] = static_cast<float>(g.normals[i][c]);
    }
  }
  r->texcoords.clear();
  for (const auto& t : g.texcoords) r->texcoords.insert(r->texcoords.end(), {t[0], t[1]});
  r->indices.resize(g.mesh.faces.size() * 3);
  for (size_t f = 0; f < g.mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) r->indices[3 * f + c] = g.mesh.faces[f][c];
  }
}

}  // namespace

extern "C" {

// Decodes up to `max_level` (-1: every level) within `max_triangles` (0: none; a
// double, as JS numbers are). As in the native glTF loader, a caller asking for
// level K may pass only the bytes up to the end of chunk K.
EMSCRIPTEN_KEEPALIVE EqmResult* eqm_decode(const uint8_t* data, uint32_t size, int32_t max_level,
                                           double max_triangles) {
  eqmesh::DecodeOptions options;
  options.max_level = max_level;
  options.max_triangles = max_triangles >= 1.0 && max_triangles < 1e15 ? static_cast<uint64_t>(max_triangles) : 0;
  options.allow_truncated = max_level >= 0;
  eqmesh::DecodeInfo info;
  eqmesh::StatusOr<eqmesh::DecodedGeometry> geometry = eqmesh::DecodeGeometry(data, size, options, &info);
  if (!geometry.ok()) return Failure(geometry.status());
  auto* r = new EqmResult;
  SetLayout(info.stream, r);
  r->level_decoded = info.levels_decoded;
  SetGeometry(*geometry, r);
  return r;
}

// The header alone (`size` may be any prefix holding it): levels, coder, chunks.
EMSCRIPTEN_KEEPALIVE EqmResult* eqm_read_info(const uint8_t* data, uint32_t size) {
  eqmesh::StatusOr<eqmesh::StreamInfo> info = eqmesh::ReadStreamInfo(data, size);
  if (!info.ok()) return Failure(info.status());
  auto* r = new EqmResult;
  SetLayout(*info, r);
  return r;
}

EMSCRIPTEN_KEEPALIVE int eqm_status(const EqmResult* r) { return r->status; }
EMSCRIPTEN_KEEPALIVE const char* eqm_status_name(int code) {
  return eqmesh::StatusCodeName(static_cast<eqmesh::StatusCode>(code));
}
EMSCRIPTEN_KEEPALIVE const char* eqm_message(const EqmResult* r) { return r->message.c_str(); }
EMSCRIPTEN_KEEPALIVE uint32_t eqm_vertex_count(const EqmResult* r) {
  return static_cast<uint32_t>(r->positions.size() / 3);
}
EMSCRIPTEN_KEEPALIVE const float* eqm_positions(const EqmResult* r) { return r->positions.data(); }
EMSCRIPTEN_KEEPALIVE const float* eqm_normals(const EqmResult* r) { return r->normals.data(); }
// TEXCOORD_0, two floats per vertex, or null when the stream has no atlas.
EMSCRIPTEN_KEEPALIVE const float* eqm_texcoords(const EqmResult* r) {
  return r->texcoords.empty() ? nullptr : r->texcoords.data();
}
EMSCRIPTEN_KEEPALIVE uint32_t eqm_index_count(const EqmResult* r) {
  return static_cast<uint32_t>(r->indices.size());
}
EMSCRIPTEN_KEEPALIVE const uint32_t* eqm_indices(const EqmResult* r) { return r->indices.data(); }
EMSCRIPTEN_KEEPALIVE int eqm_levels_in_stream(const EqmResult* r) { return r->levels_in_stream; }
EMSCRIPTEN_KEEPALIVE int eqm_level_decoded(const EqmResult* r) { return r->level_decoded; }
EMSCRIPTEN_KEEPALIVE int eqm_coder(const EqmResult* r) { return r->coder; }
EMSCRIPTEN_KEEPALIVE int eqm_chunk_count(const EqmResult* r) {
  return static_cast<int>(r->chunk_lengths.size());
}
EMSCRIPTEN_KEEPALIVE double eqm_chunk_length(const EqmResult* r, int j) {
  return j >= 0 && j < eqm_chunk_count(r) ? r->chunk_lengths[static_cast<size_t>(j)] : -1.0;
}
EMSCRIPTEN_KEEPALIVE void eqm_free(EqmResult* r) { delete r; }

}  // extern "C"

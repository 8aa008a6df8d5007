// The C API (include/eqmesh/eqmesh.h) over the C++ decoder: every entry point
// catches what the C++ side could throw (allocation failure), so no exception
// crosses into C, and every error is a status code plus a message.
#include "eqmesh/eqmesh.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "coding/decoded_geometry.h"
#include "coding/decoder.h"

struct eqmesh_progressive {
  eqmesh_decode_options options;
  std::vector<uint8_t> bytes;
  std::optional<eqmesh::StreamInfo> info;  // once the header has arrived
};

namespace {

// No valid header is longer (magic, six bytes, three varints and a float, and at
// most 15 chunk sizes of 5 bytes).
constexpr size_t kMaxHeaderBytes = 128;

void WriteError(const std::string& message, char* error, size_t error_size) {
  if (error == nullptr || error_size == 0) return;
  const size_t n = std::min(message.size(), error_size - 1);
  std::memcpy(error, message.data(), n);
  error[n] = '\0';
}

int Fail(const eqmesh::Status& status, char* error, size_t error_size) {
  WriteError(status.message(), error, error_size);
  return static_cast<int>(status.code());
}

eqmesh_decode_options OptionsOrDefault(const eqmesh_decode_options* options) {
  eqmesh_decode_options o;
  eqmesh_decode_options_init(&o);
  return options != nullptr ? *options : o;
}

template <typename T>
T* CopyOut(const std::vector<T>& values) {
  if (values.empty()) return nullptr;
  T* out = static_cast<T*>(std::malloc(values.size() * sizeof(T)));
  if (out == nullptr) throw std::bad_alloc();
  std::memcpy(out, values.data(), values.size() * sizeof(T));
  return out;
}

void FillMesh(const eqmesh::DecodedGeometry& g, int level, int levels, eqmesh_mesh* out) {
  std::vector<float> positions, normals, texcoords;
  std::vector<uint32_t> indices;
  for (size_t i = 0; i < g.mesh.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      positions.push_back(static_cast<float>(g.mesh.positions[i][c]));
      normals.push_back(static_cast<float>(g.normals[i][c]));
    }
  }
  for (const auto& t : g.texcoords) texcoords.insert(texcoords.end(), {t[0], t[1]});
  for (const eqmesh::Face& f : g.mesh.faces) indices.insert(indices.end(), f.begin(), f.end());
  eqmesh_mesh m{};
  m.vertex_count = static_cast<uint32_t>(g.mesh.positions.size());
  m.triangle_count = static_cast<uint32_t>(g.mesh.faces.size());
  m.level = level;
  m.levels = levels;
  try {
    m.positions = CopyOut(positions);
    m.normals = CopyOut(normals);
    m.texcoords = CopyOut(texcoords);
    m.indices = CopyOut(indices);
  } catch (...) {
    eqmesh_mesh_free(&m);
    throw;
  }
  *out = m;
}

// `prefix`: the bytes may end after the chosen level's chunk (as they may when
// the options limit the level).
eqmesh::Status Decode(const uint8_t* data, size_t size, const eqmesh_decode_options& o, bool prefix,
                      eqmesh_mesh* out) {
  eqmesh::DecodeOptions options;
  options.max_level = o.max_level;
  options.max_triangles = o.max_triangles;
  options.allow_truncated = prefix || o.max_level >= 0;
  eqmesh::DecodeInfo info;
  EQMESH_ASSIGN_OR_RETURN(const eqmesh::DecodedGeometry g, eqmesh::DecodeGeometry(data, size, options, &info));
  FillMesh(g, info.levels_decoded, info.levels_in_stream, out);
  return eqmesh::Status::Ok();
}

// The finest level whose chunks lie within the bytes held (-1: not the base yet).
int CompleteLevel(const eqmesh::StreamInfo& info, size_t size) {
  int level = -1;
  for (size_t k = 0; k < info.prefix_size.size(); ++k) {
    if (info.prefix_size[k] <= size) level = static_cast<int>(k);
  }
  // A zerotree stream carries all levels in one payload: every level or none.
  if (info.coder == eqmesh::bitstream::CoderId::kZerotree && level > 0 && size < info.total_size) level = 0;
  return level;
}

}  // namespace

extern "C" {

void eqmesh_decode_options_init(eqmesh_decode_options* options) {
  if (options == nullptr) return;
  options->max_level = -1;
  options->max_triangles = 0;
  options->threads = 0;
}

int eqmesh_decode(const uint8_t* data, size_t size, const eqmesh_decode_options* options, eqmesh_mesh* out,
                  char* error, size_t error_size) {
  if (out == nullptr) return Fail(eqmesh::InvalidArgument("no output mesh given"), error, error_size);
  *out = eqmesh_mesh{};
  if (data == nullptr && size > 0) return Fail(eqmesh::InvalidArgument("no data given"), error, error_size);
  try {
    const eqmesh::Status s = Decode(data, size, OptionsOrDefault(options), false, out);
    return s.ok() ? 0 : Fail(s, error, error_size);
  } catch (const std::bad_alloc&) {
    return Fail(eqmesh::ResourceLimit("out of memory"), error, error_size);
  } catch (...) {
    return Fail(eqmesh::InternalError("unexpected exception"), error, error_size);
  }
}

void eqmesh_mesh_free(eqmesh_mesh* mesh) {
  if (mesh == nullptr) return;
  std::free(mesh->positions);
  std::free(mesh->normals);
  std::free(mesh->texcoords);
  std::free(mesh->indices);
  *mesh = eqmesh_mesh{};
}

eqmesh_progressive* eqmesh_progressive_create(const eqmesh_decode_options* options) {
  auto* p = new (std::nothrow) eqmesh_progressive;
  if (p != nullptr) p->options = OptionsOrDefault(options);
  return p;
}

int eqmesh_progressive_feed(eqmesh_progressive* p, const uint8_t* data, size_t size, char* error,
                            size_t error_size) {
  if (p == nullptr || (data == nullptr && size > 0)) {
    return Fail(eqmesh::InvalidArgument("no decoder or no data given"), error, error_size);
  }
  try {
    p->bytes.insert(p->bytes.end(), data, data + size);
    if (!p->info) {
      if (p->bytes.size() >= 4 && std::memcmp(p->bytes.data(), "EQMS", 4) != 0) {
        return Fail(eqmesh::CorruptStream("eqm header: not an eqmesh stream (bad magic)"), error, error_size);
      }
      auto info = eqmesh::ReadStreamInfo(p->bytes.data(), p->bytes.size());
      // A header cut short is no error while its bytes may still come.
      if (info.ok()) {
        p->info = *info;
      } else if (info.status().code() != eqmesh::StatusCode::kCorruptStream || p->bytes.size() >= kMaxHeaderBytes) {
        return Fail(info.status(), error, error_size);
      }
    }
    if (p->info && p->bytes.size() > p->info->total_size) {
      return Fail(eqmesh::CorruptStream("more bytes than the stream's " + std::to_string(p->info->total_size)),
                  error, error_size);
    }
    return 0;
  } catch (const std::bad_alloc&) {
    return Fail(eqmesh::ResourceLimit("out of memory"), error, error_size);
  }
}

int eqmesh_progressive_level(const eqmesh_progressive* p) {
  if (p == nullptr || !p->info) return -1;
  return CompleteLevel(*p->info, p->bytes.size());
}

int eqmesh_progressive_decode(eqmesh_progressive* p, int level, eqmesh_mesh* out, char* error, size_t error_size) {
  if (out == nullptr || p == nullptr) return Fail(eqmesh::InvalidArgument("no decoder or output mesh"), error, error_size);
  *out = eqmesh_mesh{};
  const int ready = eqmesh_progressive_level(p);
  if (level < 0 || level > ready) {
    return Fail(eqmesh::InvalidArgument("level " + std::to_string(level) + " has not arrived (" +
                                        std::to_string(ready) + " has)"),
                error, error_size);
  }
  try {
    eqmesh_decode_options o = p->options;
    o.max_level = o.max_level < 0 ? level : std::min(o.max_level, level);
    const size_t size = static_cast<size_t>(p->info->prefix_size[static_cast<size_t>(
        p->info->coder == eqmesh::bitstream::CoderId::kZerotree && level > 0 ? p->info->levels : level)]);
    const eqmesh::Status s = Decode(p->bytes.data(), std::min(size, p->bytes.size()), o, true, out);
    return s.ok() ? 0 : Fail(s, error, error_size);
  } catch (const std::bad_alloc&) {
    return Fail(eqmesh::ResourceLimit("out of memory"), error, error_size);
  } catch (...) {
    return Fail(eqmesh::InternalError("unexpected exception"), error, error_size);
  }
}

void eqmesh_progressive_destroy(eqmesh_progressive* p) { delete p; }

}  // extern "C"

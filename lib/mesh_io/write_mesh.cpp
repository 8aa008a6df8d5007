// Mesh writers: OBJ and OFF as text with shortest round-trip decimals (std::to_chars),
// binary little-endian PLY, and GLB assembled here rather than through tinygltf so
// that every byte that the glTF validator checks (chunk padding, accessor min/max
// equal to the stored float32 values, index type, bufferView targets) is ours.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "mesh_io/atomic_file.h"
#include "mesh_io/mesh_io.h"

namespace eqmesh {
namespace {

using Bytes = std::vector<uint8_t>;

void Append(Bytes* out, const std::string& s) { out->insert(out->end(), s.begin(), s.end()); }

template <typename T>
void AppendLE(Bytes* out, T value) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "writer assumes a little-endian host");
  uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out->insert(out->end(), raw, raw + sizeof(T));
}

// Shortest decimal that parses back to exactly `v`.
void AppendNumber(Bytes* out, double v) {
  char buf[32];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), v);
  out->insert(out->end(), buf, r.ptr);
}

void AppendNumber(Bytes* out, uint64_t v) {
  char buf[24];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), v);
  out->insert(out->end(), buf, r.ptr);
}

Status ValidateForWriting(const Mesh& mesh, bool needs_float32) {
  const size_t n = mesh.positions.size();
  if (n > std::numeric_limits<uint32_t>::max()) return InvalidArgument("mesh has more than 2^32-1 vertices");
  for (size_t v = 0; v < n; ++v) {
    const Vec3& p = mesh.positions[v];
    if (!p.allFinite()) return InvalidArgument("vertex " + std::to_string(v) + " has a non-finite coordinate");
    if (needs_float32 && p.cwiseAbs().maxCoeff() > std::numeric_limits<float>::max()) {
      return InvalidArgument("vertex " + std::to_string(v) + " is beyond float32 range");
    }
  }
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t i : mesh.faces[f]) {
      if (i >= n) return InvalidArgument("face " + std::to_string(f) + " has vertex index " + std::to_string(i) + " out of range (" + std::to_string(n) + " vertices)");
    }
  }
  return Status::Ok();
}

Bytes EncodeObj(const Mesh& mesh) {
  Bytes out;
  out.reserve(mesh.positions.size() * 40 + mesh.faces.size() * 24 + 64);
  Append(&out, "# eqmesh: " + std::to_string(mesh.positions.size()) + " vertices, " +
                   std::to_string(mesh.faces.size()) + " faces\n");
  for (const Vec3& p : mesh.positions) {
    out.push_back('v');
    for (int k = 0; k < 3; ++k) {
      out.push_back(' ');
      AppendNumber(&out, p[k]);
    }
    out.push_back('\n');
  }
  for (const Face& f : mesh.faces) {
    out.push_back('f');
    for (uint32_t i : f) {
      out.push_back(' ');
      AppendNumber(&out, uint64_t{i} + 1);
    }
    out.push_back('\n');
  }
  return out;
}

Bytes EncodeOff(const Mesh& mesh) {
  Bytes out;
  Append(&out, "OFF\n" + std::to_string(mesh.positions.size()) + " " + std::to_string(mesh.faces.size()) + " 0\n");
  for (const Vec3& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      if (k) out.push_back(' ');
      AppendNumber(&out, p[k]);
    }
    out.push_back('\n');
  }
  for (const Face& f : mesh.faces) {
    out.push_back('3');
    for (uint32_t i : f) {
      out.push_back(' ');
      AppendNumber(&out, uint64_t{i});
    }
    out.push_back('\n');
  }
  return out;
}

Bytes EncodePly(const Mesh& mesh, const WriteOptions& options) {
  const char* coord = options.ply_double_positions ? "double" : "float";
  // int is what most PLY readers expect; uint only when indices need it.
  const bool wide = mesh.positions.size() > uint64_t{std::numeric_limits<int32_t>::max()};
  Bytes out;
  Append(&out, std::string("ply\nformat binary_little_endian 1.0\ncomment written by eqmesh\n") +
                   "element vertex " + std::to_string(mesh.positions.size()) + "\n" +
                   "property " + coord + " x\nproperty " + coord + " y\nproperty " + coord + " z\n" +
                   "element face " + std::to_string(mesh.faces.size()) + "\n" +
                   "property list uchar " + (wide ? "uint" : "int") + " vertex_indices\nend_header\n");
  for (const Vec3& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      if (options.ply_double_positions) AppendLE(&out, p[k]);
      else AppendLE(&out, static_cast<float>(p[k]));
    }
  }
  for (const Face& f : mesh.faces) {
    out.push_back(3);
    for (uint32_t i : f) AppendLE(&out, i);
  }
  return out;
}

// JSON of the single-mesh GLB; min/max are the float32 values as stored, printed
// as exact doubles, because the validator compares them with the data bit for bit.
std::string GlbJson(size_t num_vertices, size_t num_indices, bool short_indices, const float mn[3],
                    const float mx[3], size_t positions_bytes, size_t indices_bytes, size_t buffer_bytes) {
  auto vec = [](const float v[3]) {
    Bytes b;
    for (int k = 0; k < 3; ++k) {
      if (k) b.push_back(',');
      AppendNumber(&b, static_cast<double>(v[k]));
    }
    return "[" + std::string(b.begin(), b.end()) + "]";
  };
  const std::string n = std::to_string(num_vertices);
  return std::string("{\"asset\":{\"version\":\"2.0\",\"generator\":\"eqmesh\"},\"scene\":0,") +
         "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]," +
         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}]," +
         "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":" + n +
         ",\"type\":\"VEC3\",\"min\":" + vec(mn) + ",\"max\":" + vec(mx) + "}," +
         "{\"bufferView\":1,\"componentType\":" + (short_indices ? "5123" : "5125") +
         ",\"count\":" + std::to_string(num_indices) + ",\"type\":\"SCALAR\"}]," +
         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" + std::to_string(positions_bytes) +
         ",\"target\":34962},{\"buffer\":0,\"byteOffset\":" + std::to_string(positions_bytes) +
         ",\"byteLength\":" + std::to_string(indices_bytes) + ",\"target\":34963}]," +
         "\"buffers\":[{\"byteLength\":" + std::to_string(buffer_bytes) + "}]}";
}

void AppendChunk(Bytes* out, uint32_t type, const Bytes& payload, uint8_t pad) {
  const size_t padded = (payload.size() + 3) & ~size_t{3};
  AppendLE(out, static_cast<uint32_t>(padded));
  AppendLE(out, type);
  out->insert(out->end(), payload.begin(), payload.end());
  out->insert(out->end(), padded - payload.size(), pad);
}

StatusOr<Bytes> EncodeGlb(const Mesh& mesh) {
  if (mesh.faces.empty() || mesh.positions.empty()) return InvalidArgument("GLB needs at least one face");
  // 65535 is the primitive-restart value, which glTF forbids as an index.
  const bool short_indices = mesh.positions.size() <= 65535;
  Bytes bin;
  float mn[3], mx[3];
  for (int k = 0; k < 3; ++k) {
    mn[k] = std::numeric_limits<float>::infinity();
    mx[k] = -std::numeric_limits<float>::infinity();
  }
  for (const Vec3& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(p[k]);
      mn[k] = std::min(mn[k], f);
      mx[k] = std::max(mx[k], f);
      AppendLE(&bin, f);
    }
  }
  const size_t positions_bytes = bin.size();
  for (const Face& f : mesh.faces) {
    for (uint32_t i : f) {
      if (short_indices) AppendLE(&bin, static_cast<uint16_t>(i));
      else AppendLE(&bin, i);
    }
  }
  const size_t indices_bytes = bin.size() - positions_bytes;
  bin.resize((bin.size() + 3) & ~size_t{3}, 0);  // buffer length = BIN chunk length
  const std::string json = GlbJson(mesh.positions.size(), mesh.faces.size() * 3, short_indices, mn, mx,
                                   positions_bytes, indices_bytes, bin.size());
  const uint64_t total = 12 + 8 + ((json.size() + 3) & ~size_t{3}) + 8 + bin.size();
  if (total > std::numeric_limits<uint32_t>::max()) return InvalidArgument("mesh too large for one GLB (4 GiB)");
  Bytes out;
  out.reserve(static_cast<size_t>(total));
  AppendLE(&out, uint32_t{0x46546C67});  // "glTF"
  AppendLE(&out, uint32_t{2});
  AppendLE(&out, static_cast<uint32_t>(total));
  AppendChunk(&out, 0x4E4F534A, Bytes(json.begin(), json.end()), ' ');  // "JSON", space-padded
  AppendChunk(&out, 0x004E4942, bin, 0);                                 // "BIN\0"
  return out;
}

std::string ExtensionOf(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

StatusOr<std::vector<uint8_t>> WriteMeshToBytes(const Mesh& mesh, const std::string& format,
                                                const WriteOptions& options) {
  std::string f = format;
  if (!f.empty() && f[0] == '.') f.erase(0, 1);
  const bool float32 = f == "glb" || (f == "ply" && !options.ply_double_positions);
  if (f != "obj" && f != "off" && f != "ply" && f != "glb") {
    return UnsupportedFeature("cannot write mesh format '" + format + "' (expected obj, ply, off or glb)");
  }
  EQMESH_RETURN_IF_ERROR(ValidateForWriting(mesh, float32));
  if (f == "obj") return EncodeObj(mesh);
  if (f == "off") return EncodeOff(mesh);
  if (f == "ply") return EncodePly(mesh, options);
  return EncodeGlb(mesh);
}

Status WriteMesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  const StatusOr<Bytes> bytes = WriteMeshToBytes(mesh, ExtensionOf(path), options);
  if (!bytes.ok()) return bytes.status().WithContext(path);
  return WriteFileAtomically(path, *bytes);
}

}  // namespace eqmesh

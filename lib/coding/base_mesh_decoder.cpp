#include "coding/base_mesh_decoder.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include "coding/entropy/byte_io.h"

namespace eqmesh {
namespace {

// Draco 1.5.5 sizes its connectivity arrays from the edgebreaker header's counts
// before it reads a single symbol (a 70-byte kept chunk declaring 172 million faces
// asked for 689 MB at once; found by fuzz/fuzz_eqm_decode), so those counts are read
// and checked here first. Real chunks need far more than a byte per 64 faces.
constexpr uint64_t kDracoElementsBase = uint64_t{1} << 17;
constexpr uint64_t kDracoElementsPerByte = 64;

// Draco's uint32 varint: at most 5 bytes, the value taken modulo 2^32 as Draco does.
bool ReadDracoVarint(ByteReader* r, uint64_t* v) {
  const size_t start = r->offset();
  if (!r->ReadVarint(v).ok() || r->offset() - start > 5) return false;
  *v &= 0xFFFFFFFFu;
  return true;
}

// The element counts at the start of a Draco 2.2 mesh buffer (ext_spec A.3):
// header "DRACO" major minor encoder_type method flags(u16), then for edgebreaker
// traversal_type, num_encoded_vertices, num_faces, num_attribute_data (u8),
// num_encoded_symbols, num_encoded_split_symbols; for sequential num_faces,
// num_points. Whatever cannot be read is left for Draco to reject.
Status CheckDracoCounts(const uint8_t* data, size_t size, const DracoMeshLimits& limits, const std::string& what) {
  static constexpr char kMagic[5] = {'D', 'R', 'A', 'C', 'O'};
  if (size < 11 || std::memcmp(data, kMagic, 5) != 0) return Status::Ok();
  if (data[5] != 2 || data[6] != 2) {
    return CorruptStream(what + ": Draco bitstream version " + std::to_string(data[5]) + "." +
                         std::to_string(data[6]) + ", the format requires 2.2");
  }
  if ((data[10] & 0x80) != 0) return UnsupportedFeature(what + ": Draco metadata is not supported");
  ByteReader r(data + 11, size - 11, what);
  uint64_t faces = 0, vertices = 0, extra = 0;
  uint8_t byte = 0;
  if (data[8] == 1) {  // edgebreaker
    if (!r.ReadU8(&byte).ok() || !ReadDracoVarint(&r, &vertices) || !ReadDracoVarint(&r, &faces) ||
        !r.ReadU8(&byte).ok() || !ReadDracoVarint(&r, &extra) || !ReadDracoVarint(&r, &extra)) {
      return Status::Ok();
    }
    vertices += extra;  // split symbols add vertices while decoding
  } else if (data[8] == 0) {  // sequential
    if (!ReadDracoVarint(&r, &faces) || !ReadDracoVarint(&r, &vertices)) return Status::Ok();
  } else {
    return Status::Ok();
  }
  const uint64_t room = kDracoElementsBase + kDracoElementsPerByte * size;
  if (faces > limits.max_faces || faces > room || vertices > room) {
    return ResourceLimit(what + ": Draco header declares " + std::to_string(faces) + " faces / " +
                         std::to_string(vertices) + " vertices in a " + std::to_string(size) +
                         "-byte chunk (limit " + std::to_string(std::min<uint64_t>(room, limits.max_faces)) +
                         " faces, " + std::to_string(room) + " vertices)");
  }
  return Status::Ok();
}

Status CheckFaces(const Mesh& mesh, const std::string& what) {
  const size_t n = mesh.positions.size();
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const Face& f = mesh.faces[i];
    if (f[0] >= n || f[1] >= n || f[2] >= n) {
      return CorruptStream(what + ": face " + std::to_string(i) + " references a missing vertex");
    }
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      return CorruptStream(what + ": face " + std::to_string(i) + " repeats a vertex");
    }
  }
  return Status::Ok();
}

// Types ConvertValue<float> reads as plain numbers (not bool, not invalid).
bool IsNumericPositionType(draco::DataType type) {
  switch (type) {
    case draco::DT_INT8:
    case draco::DT_UINT8:
    case draco::DT_INT16:
    case draco::DT_UINT16:
    case draco::DT_INT32:
    case draco::DT_UINT32:
    case draco::DT_INT64:
    case draco::DT_UINT64:
    case draco::DT_FLOAT32:
    case draco::DT_FLOAT64:
      return true;
    default:
      return false;
  }
}

StatusOr<Mesh> ConvertDracoMesh(const draco::Mesh& dm, const DracoMeshLimits& limits,
                                const std::string& what) {
  if (dm.num_points() > limits.max_vertices || dm.num_faces() > limits.max_faces) {
    return ResourceLimit(what + ": " + std::to_string(dm.num_points()) + " vertices / " +
                         std::to_string(dm.num_faces()) + " faces exceed the stream limits");
  }
  const draco::PointAttribute* pos = dm.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (pos == nullptr || pos->num_components() != 3) {
    return CorruptStream(what + ": no 3-component position attribute");
  }
  if (!IsNumericPositionType(pos->data_type())) {
    // Draco converts a bool attribute by loading its bytes as bool: undefined
    // behaviour for any byte but 0 and 1 (found by fuzz_eqm_decode).
    return CorruptStream(what + ": position attribute of data type " +
                         std::to_string(static_cast<int>(pos->data_type())) + " (must be a number type)");
  }
  Mesh mesh;
  mesh.positions.resize(dm.num_points());
  for (uint32_t i = 0; i < dm.num_points(); ++i) {
    float xyz[3] = {0, 0, 0};
    if (!pos->ConvertValue<float>(pos->mapped_index(draco::PointIndex(i)), 3, xyz)) {
      return CorruptStream(what + ": unreadable position " + std::to_string(i));
    }
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(xyz[c])) return CorruptStream(what + ": non-finite position");
    }
    mesh.positions[i] = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  mesh.faces.resize(dm.num_faces());
  for (uint32_t i = 0; i < dm.num_faces(); ++i) {
    const draco::Mesh::Face& f = dm.face(draco::FaceIndex(i));
    mesh.faces[i] = {f[0].value(), f[1].value(), f[2].value()};
  }
  EQMESH_RETURN_IF_ERROR(CheckFaces(mesh, what));
  return mesh;
}

}  // namespace

StatusOr<Mesh> DecodeDracoMesh(const uint8_t* data, size_t size, const DracoMeshLimits& limits,
                               const std::string& what) {
  EQMESH_RETURN_IF_ERROR(CheckDracoCounts(data, size, limits, what));
  try {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) {
      return CorruptStream(what + ": Draco: " + decoded.status().error_msg_string());
    }
    const std::unique_ptr<draco::Mesh>& dm = decoded.value();
    if (dm == nullptr) return CorruptStream(what + ": Draco returned no mesh");
    return ConvertDracoMesh(*dm, limits, what);
  } catch (const std::exception& e) {
    return CorruptStream(what + ": Draco failed: " + e.what());
  } catch (...) {
    return CorruptStream(what + ": Draco failed");
  }
}

}  // namespace eqmesh

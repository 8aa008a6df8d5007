#include "coding/base_mesh_decoder.h"

#include <cmath>
#include <exception>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

namespace eqmesh {
namespace {

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

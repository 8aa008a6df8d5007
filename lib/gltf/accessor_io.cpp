#include "gltf/accessor_io.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "gltf/buffer_layout.h"

namespace eqmesh::gltf {
namespace {

struct ElementSpan {
  const unsigned char* first = nullptr;
  size_t stride = 0;
  size_t count = 0;
};

// Locates an accessor's elements and proves every byte of them lies in its buffer.
StatusOr<ElementSpan> LocateElements(const tinygltf::Model& model, int index, size_t element_size,
                                     const std::string& what) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
    return ParseError(what + " accessor " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
  if (a.sparse.isSparse) return UnsupportedFeature(what + " accessor is sparse");
  if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model.bufferViews.size()) {
    return ParseError(what + " accessor has no valid bufferView");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return ParseError(what + " bufferView refers to a missing buffer");
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  const size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
  if (stride < element_size) return ParseError(what + " byteStride is smaller than an element");
  ElementSpan span{nullptr, stride, a.count};
  if (a.count == 0) return span;
  const uint64_t needed = a.byteOffset + (static_cast<uint64_t>(a.count) - 1) * stride + element_size;
  if (needed > view.byteLength || view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    return ParseError(what + " accessor extends past the end of its buffer");
  }
  span.first = data.data() + view.byteOffset + a.byteOffset;
  return span;
}

template <typename T>
T LoadUnaligned(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

void AppendBytes(std::vector<uint8_t>* out, const void* data, size_t size) {
  const uint8_t* p = static_cast<const uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}

bool FitsFloat(const Vec3& p) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) && std::abs(p.x()) <= kMax &&
         std::abs(p.y()) <= kMax && std::abs(p.z()) <= kMax;
}

void DescribePositions(const Mesh& mesh, tinygltf::Accessor* a) {
  a->type = TINYGLTF_TYPE_VEC3;
  a->componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a->count = mesh.positions.size();
  // glTF's min / max are those of the stored float32 values, so round first.
  std::vector<double> lo(3, std::numeric_limits<double>::infinity());
  std::vector<double> hi(3, -std::numeric_limits<double>::infinity());
  for (const Vec3& p : mesh.positions) {
    for (int i = 0; i < 3; ++i) {
      const double v = static_cast<double>(static_cast<float>(p[i]));
      lo[static_cast<size_t>(i)] = std::min(lo[static_cast<size_t>(i)], v);
      hi[static_cast<size_t>(i)] = std::max(hi[static_cast<size_t>(i)], v);
    }
  }
  a->minValues = lo;
  a->maxValues = hi;
}

std::vector<uint8_t> Vec3Bytes(const std::vector<Vec3>& values) {
  std::vector<uint8_t> bytes;
  bytes.reserve(values.size() * 12);
  for (const Vec3& v : values) {
    const float f[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
    AppendBytes(&bytes, f, sizeof(f));
  }
  return bytes;
}

std::vector<uint8_t> IndexBytes(const Mesh& mesh, int component_type) {
  std::vector<uint8_t> bytes;
  for (const Face& f : mesh.faces) {
    for (uint32_t v : f) {
      if (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        const uint16_t s = static_cast<uint16_t>(v);
        AppendBytes(&bytes, &s, 2);
      } else {
        AppendBytes(&bytes, &v, 4);
      }
    }
  }
  return bytes;
}

void ClearData(tinygltf::Accessor* a) {
  a->bufferView = -1;
  a->byteOffset = 0;
  a->normalized = false;
  a->sparse = tinygltf::Accessor().sparse;
  a->minValues.clear();
  a->maxValues.clear();
}

}  // namespace

StatusOr<std::vector<Vec3>> ReadVec3Accessor(const tinygltf::Model& model, int accessor,
                                             const std::string& what) {
  EQMESH_ASSIGN_OR_RETURN(const ElementSpan span, LocateElements(model, accessor, 12, what));
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(accessor)];
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    return UnsupportedFeature(what + " is not a float VEC3 accessor");
  }
  std::vector<Vec3> out(span.count);
  for (size_t i = 0; i < span.count; ++i) {
    const unsigned char* p = span.first + i * span.stride;
    out[i] = Vec3(LoadUnaligned<float>(p), LoadUnaligned<float>(p + 4), LoadUnaligned<float>(p + 8));
    if (!out[i].allFinite()) return ParseError(what + " value " + std::to_string(i) + " is not finite");
  }
  return out;
}

namespace {

// `components` float, or normalized unsigned byte / short, values of a VEC2 /
// VEC3 / VEC4 accessor (the leading `components` of each element), no sparse.
StatusOr<std::vector<std::array<double, 4>>> ReadNormalizedVectors(const tinygltf::Model& model, int accessor,
                                                                  const std::string& what, size_t components) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= model.accessors.size()) {
    return ParseError(what + " accessor " + std::to_string(accessor) + " does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(accessor)];
  const int ct = a.componentType;
  const size_t size = ct == TINYGLTF_COMPONENT_TYPE_FLOAT                            ? 4
                      : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && a.normalized ? 2
                      : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.normalized  ? 1
                                                                                     : 0;
  const size_t stored = a.type == TINYGLTF_TYPE_VEC2 ? 2 : a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC4 ? 4 : 0;
  if (size == 0 || stored < components) {
    return UnsupportedFeature(what + " is not a float or normalized unsigned accessor of " + std::to_string(components) +
                              "+ components");
  }
  EQMESH_ASSIGN_OR_RETURN(const ElementSpan span, LocateElements(model, accessor, stored * size, what));
  std::vector<std::array<double, 4>> out(span.count);
  for (size_t i = 0; i < span.count; ++i) {
    const unsigned char* p = span.first + i * span.stride;
    for (size_t c = 0; c < components; ++c) {
      const unsigned char* q = p + c * size;
      out[i][c] = size == 4 ? LoadUnaligned<float>(q) : size == 2 ? LoadUnaligned<uint16_t>(q) / 65535.0 : *q / 255.0;
      if (!std::isfinite(out[i][c])) return ParseError(what + " value " + std::to_string(i) + " is not finite");
    }
  }
  return out;
}

}  // namespace

StatusOr<std::vector<std::array<double, 2>>> ReadTexcoordAccessor(const tinygltf::Model& model, int accessor,
                                                                   const std::string& what) {
  const tinygltf::Accessor* a = accessor >= 0 && static_cast<size_t>(accessor) < model.accessors.size()
                                    ? &model.accessors[static_cast<size_t>(accessor)] : nullptr;
  if (a != nullptr && a->type != TINYGLTF_TYPE_VEC2) return UnsupportedFeature(what + " is not a VEC2 accessor");
  EQMESH_ASSIGN_OR_RETURN(const auto values, ReadNormalizedVectors(model, accessor, what, 2));
  std::vector<std::array<double, 2>> out(values.size());
  for (size_t i = 0; i < values.size(); ++i) out[i] = {values[i][0], values[i][1]};
  return out;
}

StatusOr<std::vector<std::array<double, 4>>> ReadTangentAccessor(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor* a = accessor >= 0 && static_cast<size_t>(accessor) < model.accessors.size()
                                    ? &model.accessors[static_cast<size_t>(accessor)] : nullptr;
  if (a != nullptr && (a->type != TINYGLTF_TYPE_VEC4 || a->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)) {
    return UnsupportedFeature("TANGENT is not a float VEC4 accessor");
  }
  return ReadNormalizedVectors(model, accessor, "TANGENT", 4);
}

StatusOr<std::vector<std::array<double, 3>>> ReadColorAccessor(const tinygltf::Model& model, int accessor,
                                                                const std::string& what) {
  EQMESH_ASSIGN_OR_RETURN(const auto values, ReadNormalizedVectors(model, accessor, what, 3));
  std::vector<std::array<double, 3>> out(values.size());
  for (size_t i = 0; i < values.size(); ++i) out[i] = {values[i][0], values[i][1], values[i][2]};
  return out;
}

StatusOr<std::vector<uint32_t>> ReadIndexAccessor(const tinygltf::Model& model, int accessor,
                                                  size_t vertex_count) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= model.accessors.size()) {
    return ParseError("indices accessor " + std::to_string(accessor) + " does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(accessor)];
  const int ct = a.componentType;
  const size_t size = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                     : 0;
  if (size == 0 || a.type != TINYGLTF_TYPE_SCALAR) return ParseError("indices are not unsigned SCALAR");
  EQMESH_ASSIGN_OR_RETURN(const ElementSpan span, LocateElements(model, accessor, size, "indices"));
  std::vector<uint32_t> out(span.count);
  for (size_t i = 0; i < span.count; ++i) {
    const unsigned char* p = span.first + i * span.stride;
    out[i] = size == 1 ? *p : size == 2 ? LoadUnaligned<uint16_t>(p) : LoadUnaligned<uint32_t>(p);
    if (out[i] >= vertex_count) {
      return ParseError("index " + std::to_string(i) + " is " + std::to_string(out[i]) +
                        ", not below the vertex count " + std::to_string(vertex_count));
    }
  }
  return out;
}

StatusOr<Mesh> ReadTrianglePrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive) {
  const auto pos = primitive.attributes.find("POSITION");
  if (pos == primitive.attributes.end()) return ParseError("primitive has no POSITION");
  Mesh mesh;
  EQMESH_ASSIGN_OR_RETURN(mesh.positions, ReadVec3Accessor(model, pos->second, "POSITION"));
  std::vector<uint32_t> indices;
  if (primitive.indices >= 0) {
    EQMESH_ASSIGN_OR_RETURN(indices, ReadIndexAccessor(model, primitive.indices, mesh.positions.size()));
  } else {
    if (mesh.positions.size() > 0xFFFFFFFFu) return ResourceLimit("too many vertices");
    indices.resize(mesh.positions.size());
    for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
  }
  if (indices.size() % 3 != 0) return ParseError("index count is not a multiple of 3");
  mesh.faces.reserve(indices.size() / 3);
  for (size_t i = 0; i + 2 < indices.size(); i += 3) mesh.faces.push_back({indices[i], indices[i + 1], indices[i + 2]});
  return mesh;
}

namespace {

std::vector<uint8_t> Vec2Bytes(const std::vector<std::array<float, 2>>& values) {
  std::vector<uint8_t> out;
  out.reserve(values.size() * 8);
  for (const auto& v : values) AppendBytes(&out, v.data(), 8);
  return out;
}

// TEXCOORD_0 as float VEC2 (glTF requires no min / max for it).
int WriteTexcoords(tinygltf::Model* model, const std::vector<std::array<float, 2>>& texcoords, int accessor,
                   bool store_data) {
  tinygltf::Accessor& a = model->accessors[static_cast<size_t>(accessor)];
  ClearData(&a);
  a.type = TINYGLTF_TYPE_VEC2;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = texcoords.size();
  if (!store_data) return -1;
  const std::vector<uint8_t> bytes = Vec2Bytes(texcoords);
  a.bufferView = AppendBufferView(model, bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
  return a.bufferView;
}

}  // namespace

StatusOr<std::vector<int>> WriteGeometry(tinygltf::Model* model, const Mesh& mesh,
                                         const GeometryAccessors& accessors, bool store_data) {
  return WriteGeometry(model, {&mesh, nullptr, nullptr}, accessors, store_data);
}

StatusOr<std::vector<int>> WriteGeometry(tinygltf::Model* model, const GeometryData& data,
                                         const GeometryAccessors& accessors, bool store_data) {
  const Mesh& mesh = *data.mesh;
  if (data.texcoords != nullptr && data.texcoords->size() != mesh.positions.size()) {
    return InternalError("texture coordinates do not match the vertices");
  }
  if (data.normals != nullptr && data.normals->size() != mesh.positions.size()) {
    return InternalError("normals do not match the vertices");
  }
  if (mesh.positions.empty() || mesh.faces.empty()) return InvalidMesh("decoded mesh is empty");
  for (const Vec3& p : mesh.positions) {
    if (!FitsFloat(p)) return InvalidMesh("a coordinate is not finite or beyond float range");
  }
  const int index_type = mesh.positions.size() <= 0xFFFFu ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                                          : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  tinygltf::Accessor& pos = model->accessors[static_cast<size_t>(accessors.position)];
  ClearData(&pos);
  DescribePositions(mesh, &pos);
  std::vector<int> views;
  if (store_data) {
    const std::vector<uint8_t> bytes = Vec3Bytes(mesh.positions);
    pos.bufferView = AppendBufferView(model, bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    views.push_back(pos.bufferView);
  }
  if (accessors.normal >= 0) {
    tinygltf::Accessor& nor = model->accessors[static_cast<size_t>(accessors.normal)];
    ClearData(&nor);
    nor.type = TINYGLTF_TYPE_VEC3;
    nor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    nor.count = mesh.positions.size();
    if (store_data) {
      const std::vector<uint8_t> bytes = Vec3Bytes(data.normals != nullptr ? *data.normals : UnitVertexNormals(mesh));
      nor.bufferView = AppendBufferView(model, bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
      views.push_back(nor.bufferView);
    }
  }
  tinygltf::Accessor& idx = model->accessors[static_cast<size_t>(accessors.indices)];
  ClearData(&idx);
  idx.type = TINYGLTF_TYPE_SCALAR;
  idx.componentType = index_type;
  idx.count = mesh.faces.size() * 3;
  if (store_data) {
    const std::vector<uint8_t> bytes = IndexBytes(mesh, index_type);
    idx.bufferView = AppendBufferView(model, bytes.data(), bytes.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    views.push_back(idx.bufferView);
  }
  if (accessors.texcoord >= 0 && data.texcoords != nullptr) {
    const int view = WriteTexcoords(model, *data.texcoords, accessors.texcoord, store_data);
    if (view >= 0) views.push_back(view);
  }
  return views;
}

StatusOr<tinygltf::Model> ModelFromMesh(const Mesh& mesh) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "eqmesh";
  model.accessors.resize(3);
  EQMESH_RETURN_IF_ERROR(WriteGeometry(&model, mesh, {0, 1, 2}, true).status());
  tinygltf::Primitive primitive;
  primitive.attributes = {{"POSITION", 0}, {"NORMAL", 1}};
  primitive.indices = 2;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  model.meshes.emplace_back();
  model.meshes[0].primitives.push_back(primitive);
  model.nodes.emplace_back();
  model.nodes[0].mesh = 0;
  model.scenes.emplace_back();
  model.scenes[0].nodes = {0};
  model.defaultScene = 0;
  return model;
}

}  // namespace eqmesh::gltf

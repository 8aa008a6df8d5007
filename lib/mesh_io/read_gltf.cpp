// glTF 2.0 / GLB through tinygltf: the TRIANGLES primitives of every mesh reachable
// from the default scene (or, without scenes, from every root node), with node
// transforms applied, flattened into one Mesh. tinygltf parses the JSON and buffers;
// it does not check that accessors lie inside their buffers, so that is done here
// before any byte is read. Images are never decoded.
#include <algorithm>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cstring>
#include <limits>

#include "mesh_io/mesh_reader_support.h"

namespace eqmesh::io_internal {
namespace {

// Instancing lets a small file describe a huge mesh; the flattened output may hold
// at most this many vertices + faces per input byte (plus a floor for tiny files).
constexpr uint64_t kMaxGltfAmplification = 64;
constexpr uint64_t kMinFlattenedBudget = uint64_t{1} << 24;

bool SkipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
  return true;
}

// Where an accessor's elements lie inside their buffer, bounds already checked.
struct AccessorView {
  const uint8_t* data = nullptr;
  size_t stride = 0;
  size_t count = 0;
  int component_type = 0;
  bool normalized = false;
};

int ComponentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

size_t ComponentSize(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// Component c of element i as a double (normalized integers map to [-1, 1] / [0, 1]).
double LoadComponent(const AccessorView& v, size_t i, int c) {
  const uint8_t* p = v.data + i * v.stride + static_cast<size_t>(c) * ComponentSize(v.component_type);
  auto load = [p](auto t) { std::memcpy(&t, p, sizeof(t)); return t; };
  switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float{});
    case TINYGLTF_COMPONENT_TYPE_BYTE: return v.normalized ? std::max(load(int8_t{}) / 127.0, -1.0) : load(int8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? load(uint8_t{}) / 255.0 : load(uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT: return v.normalized ? std::max(load(int16_t{}) / 32767.0, -1.0) : load(int16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return v.normalized ? load(uint16_t{}) / 65535.0 : load(uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(uint32_t{});
  }
  return 0.0;
}

class GltfFlattener {
 public:
  GltfFlattener(const tinygltf::Model& model, const std::string& name, uint64_t budget, ReadReport* report)
      : model_(model), name_(name), budget_(budget), report_(report) {}

  Status Run() {
    std::vector<int> roots;
    EQMESH_RETURN_IF_ERROR(RootNodes(&roots));
    std::vector<bool> visited(model_.nodes.size(), false);
    std::vector<std::pair<int, Eigen::Matrix4d>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [node_index, parent] = stack.back();
      stack.pop_back();
      if (node_index < 0 || static_cast<size_t>(node_index) >= model_.nodes.size()) {
        return ParseError(name_ + ": node index " + std::to_string(node_index) + " out of range");
      }
      // glTF nodes form a forest; a second visit means a cycle or a shared child.
      if (visited[node_index]) return ParseError(name_ + ": node " + std::to_string(node_index) + " is reached twice (node graph is not a tree)");
      visited[node_index] = true;
      const tinygltf::Node& node = model_.nodes[node_index];
      Eigen::Matrix4d world;
      EQMESH_RETURN_IF_ERROR(LocalTransform(node, node_index, &world));
      world = parent * world;
      if (node.mesh >= 0) EQMESH_RETURN_IF_ERROR(AddMesh(node.mesh, world));
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, world);
    }
    return Status::Ok();
  }

  MeshBuilder& builder() { return builder_; }

 private:
  Status RootNodes(std::vector<int>* roots) const {
    if (!model_.scenes.empty()) {
      const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(s) >= model_.scenes.size()) return ParseError(name_ + ": default scene " + std::to_string(s) + " does not exist");
      *roots = model_.scenes[s].nodes;
      return Status::Ok();
    }
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const tinygltf::Node& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<size_t>(c) < is_child.size()) is_child[c] = true;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!is_child[i]) roots->push_back(static_cast<int>(i));
    return Status::Ok();
  }

  Status LocalTransform(const tinygltf::Node& node, int index, Eigen::Matrix4d* m) const {
    *m = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
      for (int i = 0; i < 16; ++i) (*m)(i % 4, i / 4) = node.matrix[i];  // column-major
      return Status::Ok();
    }
    if (!node.matrix.empty()) return ParseError(name_ + ": node " + std::to_string(index) + ": matrix must have 16 numbers");
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (node.translation.size() == 3) t.translate(Vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) {
      // glTF stores quaternions as (x, y, z, w).
      Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (q.norm() == 0.0) return ParseError(name_ + ": node " + std::to_string(index) + ": zero rotation quaternion");
      t.rotate(q.normalized());
    }
    if (node.scale.size() == 3) t.scale(Vec3(node.scale[0], node.scale[1], node.scale[2]));
    *m = t.matrix();
    return Status::Ok();
  }

  Status ViewAccessor(int index, int want_type, const std::string& what, AccessorView* view) const {
    const std::string where = name_ + ": " + what + " accessor " + std::to_string(index);
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size()) return ParseError(where + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[index];
    if (a.sparse.isSparse) return UnsupportedFeature(where + " is sparse (not supported)");
    if (a.type != want_type) return ParseError(where + " has the wrong type");
    const size_t elem = ComponentSize(a.componentType) * static_cast<size_t>(ComponentCount(a.type));
    if (elem == 0) return ParseError(where + " has an unsupported component type " + std::to_string(a.componentType));
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model_.bufferViews.size()) return ParseError(where + " has no valid bufferView");
    const tinygltf::BufferView& bv = model_.bufferViews[a.bufferView];
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model_.buffers.size()) return ParseError(where + ": bufferView has no valid buffer");
    const std::vector<unsigned char>& buf = model_.buffers[bv.buffer].data;
    const size_t stride = bv.byteStride ? bv.byteStride : elem;
    if (stride < elem) return ParseError(where + ": byteStride " + std::to_string(stride) + " is smaller than the element");
    // All in uint64 with explicit bounds, so hostile offsets cannot wrap around.
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset) return ParseError(where + ": bufferView exceeds its buffer");
    if (a.count == 0) return ParseError(where + " is empty");
    if (a.byteOffset > bv.byteLength || (a.count - 1) > (bv.byteLength - a.byteOffset) / stride ||
        (a.count - 1) * stride + elem > bv.byteLength - a.byteOffset) {
      return ParseError(where + ": " + std::to_string(a.count) + " elements exceed the bufferView");
    }
    view->data = buf.data() + bv.byteOffset + a.byteOffset;
    view->stride = stride;
    view->count = a.count;
    view->component_type = a.componentType;
    view->normalized = a.normalized;
    return Status::Ok();
  }

  Status Spend(uint64_t amount) {
    if (amount > budget_) {
      return ResourceLimit(name_ + ": flattened scene exceeds " + std::to_string(kMaxGltfAmplification) +
                           " vertices+faces per input byte (too much instancing)");
    }
    budget_ -= amount;
    return Status::Ok();
  }

  Status AddMesh(int mesh_index, const Eigen::Matrix4d& world) {
    if (static_cast<size_t>(mesh_index) >= model_.meshes.size()) return ParseError(name_ + ": mesh " + std::to_string(mesh_index) + " does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
        ++report_->primitives_skipped;
        continue;
      }
      const Status s = AddPrimitive(prim, world);
      if (!s.ok()) return Status(s.code(), s.message() + " (mesh " + std::to_string(mesh_index) + ", primitive " + std::to_string(p) + ")");
    }
    return Status::Ok();
  }

  Status AddPrimitive(const tinygltf::Primitive& prim, const Eigen::Matrix4d& world) {
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) return ParseError(name_ + ": primitive has no POSITION");
    AccessorView positions;
    EQMESH_RETURN_IF_ERROR(ViewAccessor(pos->second, TINYGLTF_TYPE_VEC3, "POSITION", &positions));
    const size_t base = builder_.num_positions();
    EQMESH_RETURN_IF_ERROR(Spend(positions.count));
    for (size_t i = 0; i < positions.count; ++i) {
      const Eigen::Vector4d p(LoadComponent(positions, i, 0), LoadComponent(positions, i, 1), LoadComponent(positions, i, 2), 1.0);
      const Eigen::Vector4d q = world * p;
      builder_.AddPosition(q.x(), q.y(), q.z());
    }
    if (base + positions.count > std::numeric_limits<uint32_t>::max()) return ResourceLimit(name_ + ": more than 2^32-1 vertices");
    // A mirroring transform turns CCW into CW; glTF says to flip the winding back.
    const bool flip = world.topLeftCorner<3, 3>().determinant() < 0.0;
    return AddTriangles(prim, positions.count, static_cast<uint32_t>(base), flip);
  }

  Status AddTriangles(const tinygltf::Primitive& prim, size_t num_positions, uint32_t base, bool flip) {
    AccessorView idx;
    size_t count = num_positions;
    if (prim.indices >= 0) {
      EQMESH_RETURN_IF_ERROR(ViewAccessor(prim.indices, TINYGLTF_TYPE_SCALAR, "indices", &idx));
      if (idx.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || idx.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
          idx.component_type == TINYGLTF_COMPONENT_TYPE_SHORT) {
        return ParseError(name_ + ": indices must be unsigned integers");
      }
      count = idx.count;
    }
    if (count % 3 != 0) return ParseError(name_ + ": TRIANGLES primitive has " + std::to_string(count) + " indices, not a multiple of 3");
    EQMESH_RETURN_IF_ERROR(Spend(count / 3));
    for (size_t t = 0; t < count; t += 3) {
      uint32_t c[3];
      for (int k = 0; k < 3; ++k) {
        const double v = prim.indices >= 0 ? LoadComponent(idx, t + k, 0) : static_cast<double>(t + k);
        if (v >= static_cast<double>(num_positions)) {
          return ParseError(name_ + ": index " + std::to_string(static_cast<uint64_t>(v)) + " out of range (" +
                            std::to_string(num_positions) + " vertices)");
        }
        c[k] = base + static_cast<uint32_t>(v);
      }
      if (flip) std::swap(c[1], c[2]);
      builder_.AddTriangle(c[0], c[1], c[2]);
    }
    return Status::Ok();
  }

  const tinygltf::Model& model_;
  const std::string& name_;
  uint64_t budget_;
  ReadReport* report_;
  MeshBuilder builder_;
};

Status LoadModel(const uint8_t* data, size_t size, bool binary, const std::string& name, const std::string& base_dir,
                 tinygltf::Model* model, ReadReport* report) {
  if (size > std::numeric_limits<unsigned int>::max()) return ResourceLimit(name + ": glTF larger than 4 GiB");
  if (binary) EQMESH_RETURN_IF_ERROR(CheckGlbChunkLengths(data, size, name));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(SkipImage, nullptr);
  std::string err, warn;
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(model, &err, &warn, data, static_cast<unsigned int>(size), base_dir)
                : loader.LoadASCIIFromString(model, &err, &warn, reinterpret_cast<const char*>(data),
                                             static_cast<unsigned int>(size), base_dir);
  } catch (const std::exception& e) {
    return ParseError(name + ": glTF parser failed: " + e.what());
  } catch (...) {
    return ParseError(name + ": glTF parser failed");
  }
  auto one_line = [](std::string s) {
    for (char& c : s) if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
  };
  if (!ok) return ParseError(name + ": invalid " + (binary ? "GLB" : "glTF") + ": " + (err.empty() ? "parse failed" : one_line(err)));
  if (!warn.empty()) report->notes.push_back("tinygltf: " + one_line(warn));
  return Status::Ok();
}

// Whether the glTF JSON (a .gltf, or a GLB's first chunk) lists
// EXT_normal_mesh_compression among the extensions it uses: such a file's
// placeholder accessors hold no data, so this reader (which decodes nothing)
// must not take it for a broken file.
bool NamesCompressionExtension(const uint8_t* data, size_t size, bool binary) {
  size_t begin = 0, end = size;
  if (binary) {
    if (size < 20) return false;
    uint32_t length = 0;
    for (int i = 0; i < 4; ++i) length |= static_cast<uint32_t>(data[12 + i]) << (8 * i);
    begin = 20;
    end = std::min<size_t>(size, 20 + static_cast<size_t>(length));
  }
  static const std::string kName = "\"EXT_normal_mesh_compression\"";
  const char* text = reinterpret_cast<const char*>(data);
  return std::search(text + begin, text + end, kName.begin(), kName.end()) != text + end;
}

}  // namespace

StatusOr<Mesh> ReadGltf(const uint8_t* data, size_t size, bool binary, const std::string& name,
                        const std::string& base_dir, ReadReport* report) {
  report->format = binary ? "glb" : "gltf";
  if (size == 0) return ParseError(name + ": empty file");
  if (binary) EQMESH_RETURN_IF_ERROR(CheckGlbChunkLengths(data, size, name));
  if (NamesCompressionExtension(data, size, binary)) {
    return UnsupportedFeature(name + ": geometry compressed with EXT_normal_mesh_compression; decode it first "
                                     "(eqmesh decode " + name + " OUT)");
  }
  tinygltf::Model model;
  EQMESH_RETURN_IF_ERROR(LoadModel(data, size, binary, name, base_dir, &model, report));
  uint64_t input_bytes = size;
  for (const tinygltf::Buffer& b : model.buffers) input_bytes += b.data.size();
  const uint64_t budget = std::max(kMinFlattenedBudget, input_bytes * kMaxGltfAmplification);
  GltfFlattener flattener(model, name, budget, report);
  EQMESH_RETURN_IF_ERROR(flattener.Run());
  if (report->primitives_skipped > 0) {
    report->notes.push_back(std::to_string(report->primitives_skipped) + " non-TRIANGLES primitives skipped");
  }
  return FinishMesh(std::move(flattener.builder()), name, report);
}

}  // namespace eqmesh::io_internal

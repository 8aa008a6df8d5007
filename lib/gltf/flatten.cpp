// FlattenToMesh (gltf_loader.h): scene graph -> one world-space triangle mesh.
#include <algorithm>

#include <Eigen/Geometry>

#include "gltf/accessor_io.h"
#include "gltf/gltf_loader.h"

namespace eqmesh::gltf {
namespace {

using Transform = Eigen::Affine3d;

Transform LocalTransform(const tinygltf::Node& node) {
  Transform t = Transform::Identity();
  if (node.matrix.size() == 16) {
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<size_t>(c * 4 + r)];  // column major
    t.matrix() = m;
    return t;
  }
  if (node.translation.size() == 3) t.translate(Vec3(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4) {
    t.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
  }
  if (node.scale.size() == 3) t.scale(Vec3(node.scale[0], node.scale[1], node.scale[2]));
  return t;
}

// Instancing may repeat a mesh, within the readers' rule (mesh_io.h): at most this
// many flattened vertices + faces per byte of the model's buffers (at least 2^24).
constexpr uint64_t kMaxAmplification = 64;
constexpr uint64_t kMinBudget = uint64_t{1} << 24;

uint64_t Budget(const tinygltf::Model& model) {
  uint64_t bytes = 0;
  for (const tinygltf::Buffer& b : model.buffers) bytes += b.data.size();
  return std::max(kMinBudget, kMaxAmplification * bytes);
}

}  // namespace

Status SpendBudget(uint64_t cost, uint64_t* budget) {
  if (cost > *budget) {
    return ResourceLimit("the flattened scene exceeds " + std::to_string(kMaxAmplification) +
                         " vertices+faces per buffer byte (too much instancing)");
  }
  *budget -= cost;
  return Status::Ok();
}

uint64_t FlattenBudget(const tinygltf::Model& model) { return Budget(model); }

void AppendTransformed(const Mesh& part, const Eigen::Affine3d& world, Mesh* out) {
  const uint32_t offset = static_cast<uint32_t>(out->positions.size());
  for (const Vec3& v : part.positions) out->positions.push_back(world * v);
  for (const Face& f : part.faces) out->faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

namespace {

class SceneWalker {
 public:
  SceneWalker(const tinygltf::Model& model, const PrimitiveVisitor& visit)
      : model_(model), visit_(visit), visited_(model.nodes.size(), false) {}

  // glTF node graphs are forests. A hostile file may contain cycles or share a
  // child (node i -> i+1 twice, 40 times over, is 2^40 visits): refused.
  Status Visit(int node_index, const Transform& parent, size_t depth) {
    if (node_index < 0 || static_cast<size_t>(node_index) >= model_.nodes.size()) {
      return ParseError("node " + std::to_string(node_index) + " does not exist");
    }
    if (depth > model_.nodes.size()) return ParseError("the node hierarchy has a cycle");
    if (visited_[static_cast<size_t>(node_index)]) {
      return ParseError("node " + std::to_string(node_index) + " is reached twice (the node graph is not a tree)");
    }
    visited_[static_cast<size_t>(node_index)] = true;
    const tinygltf::Node& node = model_.nodes[static_cast<size_t>(node_index)];
    const Transform world = parent * LocalTransform(node);
    if (node.mesh >= 0) EQMESH_RETURN_IF_ERROR(AppendMesh(node.mesh, world));
    for (int child : node.children) EQMESH_RETURN_IF_ERROR(Visit(child, world, depth + 1));
    return Status::Ok();
  }


 private:
  Status AppendMesh(int mesh_index, const Transform& world) {
    if (static_cast<size_t>(mesh_index) >= model_.meshes.size()) {
      return ParseError("mesh " + std::to_string(mesh_index) + " does not exist");
    }
    const auto& primitives = model_.meshes[static_cast<size_t>(mesh_index)].primitives;
    for (size_t p = 0; p < primitives.size(); ++p) {
      const int mode = primitives[p].mode;
      if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES) continue;
      const std::string label = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
      EQMESH_RETURN_IF_ERROR(visit_(primitives[p], label, world));
    }
    return Status::Ok();
  }

  const tinygltf::Model& model_;
  const PrimitiveVisitor& visit_;
  std::vector<bool> visited_;
};

std::vector<int> RootNodes(const tinygltf::Model& model) {
  if (!model.scenes.empty()) {
    const size_t scene = model.defaultScene >= 0 ? static_cast<size_t>(model.defaultScene) : 0;
    if (scene < model.scenes.size()) return model.scenes[scene].nodes;
  }
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const tinygltf::Node& n : model.nodes)
    for (int c : n.children)
      if (c >= 0 && static_cast<size_t>(c) < is_child.size()) is_child[static_cast<size_t>(c)] = true;
  std::vector<int> roots;
  for (size_t i = 0; i < is_child.size(); ++i)
    if (!is_child[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

}  // namespace

Status VisitScenePrimitives(const tinygltf::Model& model, const PrimitiveVisitor& visit) {
  SceneWalker walker(model, visit);
  for (int root : RootNodes(model)) EQMESH_RETURN_IF_ERROR(walker.Visit(root, Transform::Identity(), 0));
  return Status::Ok();
}

StatusOr<Mesh> FlattenToMesh(const tinygltf::Model& model) {
  uint64_t budget = Budget(model);
  Mesh out;
  const PrimitiveVisitor append = [&](const tinygltf::Primitive& primitive, const std::string& label,
                                     const Transform& world) -> Status {
    auto part = ReadTrianglePrimitive(model, primitive);
    if (!part.ok()) return part.status().WithContext(label);
    EQMESH_RETURN_IF_ERROR(SpendBudget(part->positions.size() + part->faces.size(), &budget));
    AppendTransformed(*part, world, &out);
    return Status::Ok();
  };
  EQMESH_RETURN_IF_ERROR(VisitScenePrimitives(model, append));
  if (out.faces.empty()) return InvalidMesh("the scene has no triangles");
  return out;
}

}  // namespace eqmesh::gltf

#include "gltf/buffer_layout.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "gltf/extension.h"

namespace eqmesh::gltf {
namespace {

constexpr char kDraco[] = "KHR_draco_mesh_compression";
constexpr char kInstancing[] = "EXT_mesh_gpu_instancing";
constexpr char kMeshopt[] = "EXT_meshopt_compression";

size_t AlignUp(size_t n) { return (n + 3) & ~size_t{3}; }

using IndexVisitor = std::function<void(int*)>;

// tinygltf::Value has no mutable accessors: references inside extension objects are
// read, remapped and written back.
void VisitValueIndex(tinygltf::Value* object, const std::string& key, const IndexVisitor& visit) {
  if (!object->IsObject() || !object->Has(key) || !object->Get(key).IsNumber()) return;
  int index = object->Get(key).GetNumberAsInt();
  visit(&index);
  tinygltf::Value::Object copy = object->Get<tinygltf::Value::Object>();
  copy[key] = tinygltf::Value(index);
  *object = tinygltf::Value(std::move(copy));
}

void VisitValueObjectIndices(tinygltf::Value* object, const std::string& key, const IndexVisitor& visit) {
  if (!object->IsObject() || !object->Has(key) || !object->Get(key).IsObject()) return;
  tinygltf::Value::Object copy = object->Get<tinygltf::Value::Object>();
  tinygltf::Value inner = copy[key];
  for (const std::string& name : inner.Keys()) VisitValueIndex(&inner, name, visit);
  copy[key] = inner;
  *object = tinygltf::Value(std::move(copy));
}

void ForEachAccessorReference(tinygltf::Model* model, const IndexVisitor& visit) {
  for (tinygltf::Mesh& mesh : model->meshes) {
    for (tinygltf::Primitive& p : mesh.primitives) {
      for (auto& [semantic, index] : p.attributes) visit(&index);
      if (p.indices >= 0) visit(&p.indices);
      for (auto& target : p.targets)
        for (auto& [semantic, index] : target) visit(&index);
      auto ext = p.extensions.find(kExtensionName);
      if (ext != p.extensions.end()) VisitValueObjectIndices(&ext->second, "attributes", visit);
    }
  }
  for (tinygltf::Animation& animation : model->animations) {
    for (tinygltf::AnimationSampler& s : animation.samplers) {
      visit(&s.input);
      visit(&s.output);
    }
  }
  for (tinygltf::Skin& skin : model->skins) {
    if (skin.inverseBindMatrices >= 0) visit(&skin.inverseBindMatrices);
  }
  for (tinygltf::Node& node : model->nodes) {
    auto ext = node.extensions.find(kInstancing);
    if (ext != node.extensions.end()) VisitValueObjectIndices(&ext->second, "attributes", visit);
  }
}

void ForEachViewReference(tinygltf::Model* model, const IndexVisitor& visit) {
  for (tinygltf::Accessor& a : model->accessors) {
    if (a.bufferView >= 0) visit(&a.bufferView);
    if (a.sparse.isSparse) {
      visit(&a.sparse.indices.bufferView);
      visit(&a.sparse.values.bufferView);
    }
  }
  for (tinygltf::Image& image : model->images) {
    if (image.bufferView >= 0) visit(&image.bufferView);
  }
  for (tinygltf::Mesh& mesh : model->meshes) {
    for (tinygltf::Primitive& p : mesh.primitives) {
      for (const char* name : {kDraco, kExtensionName}) {
        auto ext = p.extensions.find(name);
        if (ext != p.extensions.end()) VisitValueIndex(&ext->second, "bufferView", visit);
      }
    }
  }
}

// Drops unreferenced candidates among `count` objects; returns old -> new index
// (-1 for dropped), or an empty vector when nothing is dropped.
std::vector<int> PlanRemoval(size_t count, const std::set<int>& candidates, const std::vector<int>& uses) {
  std::vector<int> remap(count);
  int next = 0;
  bool any = false;
  for (size_t i = 0; i < count; ++i) {
    const bool drop = candidates.count(static_cast<int>(i)) != 0 && uses[i] == 0;
    any = any || drop;
    remap[i] = drop ? -1 : next++;
  }
  if (!any) remap.clear();
  return remap;
}

template <typename T>
void EraseDropped(std::vector<T>* items, const std::vector<int>& remap) {
  std::vector<T> kept;
  kept.reserve(items->size());
  for (size_t i = 0; i < items->size(); ++i) {
    if (remap[i] >= 0) kept.push_back(std::move((*items)[i]));
  }
  *items = std::move(kept);
}

template <typename Objects, typename ForEach>
Status RemoveUnreferenced(tinygltf::Model* model, Objects* objects, const std::set<int>& candidates,
                          ForEach for_each, const char* what) {
  const int size = static_cast<int>(objects->size());
  std::vector<int> uses(objects->size(), 0);
  bool dangling = false;
  for_each(model, [&](int* index) {
    if (*index >= 0 && *index < size) ++uses[static_cast<size_t>(*index)];
    else dangling = true;
  });
  if (dangling) return ParseError(std::string("a reference to a missing ") + what);
  const std::vector<int> remap = PlanRemoval(objects->size(), candidates, uses);
  if (remap.empty()) return Status::Ok();
  for_each(model, [&](int* index) { *index = remap[static_cast<size_t>(*index)]; });
  EraseDropped(objects, remap);
  return Status::Ok();
}

}  // namespace

int AppendBufferView(tinygltf::Model* model, const uint8_t* data, size_t size, int target) {
  if (model->buffers.empty()) model->buffers.emplace_back();
  std::vector<unsigned char>& bytes = model->buffers[0].data;
  bytes.resize(AlignUp(bytes.size()), 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bytes.size();
  view.byteLength = size;
  view.target = target;
  bytes.insert(bytes.end(), data, data + size);
  model->bufferViews.push_back(view);
  return static_cast<int>(model->bufferViews.size()) - 1;
}

Status RemoveUnusedData(tinygltf::Model* model, const std::set<int>& candidate_accessors,
                        const std::set<int>& candidate_views) {
  EQMESH_RETURN_IF_ERROR(RemoveUnreferenced(model, &model->accessors, candidate_accessors,
                                            ForEachAccessorReference, "accessor"));
  return RemoveUnreferenced(model, &model->bufferViews, candidate_views, ForEachViewReference,
                            "bufferView");
}

Status MergeBuffers(tinygltf::Model* model) {
  const auto& used = model->extensionsUsed;
  if (std::find(used.begin(), used.end(), kMeshopt) != used.end()) {
    return UnsupportedFeature(std::string(kMeshopt) + " buffers cannot be repacked");
  }
  std::vector<unsigned char> merged;
  for (size_t i = 0; i < model->bufferViews.size(); ++i) {
    tinygltf::BufferView& view = model->bufferViews[i];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model->buffers.size()) {
      return ParseError("bufferView " + std::to_string(i) + " refers to a missing buffer");
    }
    const std::vector<unsigned char>& source = model->buffers[static_cast<size_t>(view.buffer)].data;
    if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset) {
      return ParseError("bufferView " + std::to_string(i) + " extends past the end of buffer " +
                        std::to_string(view.buffer));
    }
    merged.resize(AlignUp(merged.size()), 0);
    const size_t offset = merged.size();
    merged.insert(merged.end(), source.begin() + static_cast<std::ptrdiff_t>(view.byteOffset),
                  source.begin() + static_cast<std::ptrdiff_t>(view.byteOffset + view.byteLength));
    view.buffer = 0;
    view.byteOffset = offset;
  }
  model->buffers.clear();
  if (!merged.empty()) {
    merged.resize(AlignUp(merged.size()), 0);
    tinygltf::Buffer buffer;
    buffer.data = std::move(merged);
    model->buffers.push_back(std::move(buffer));
  }
  return Status::Ok();
}

StatusOr<const uint8_t*> BufferViewData(const tinygltf::Model& model, int view_index, const std::string& what) {
  if (view_index < 0 || static_cast<size_t>(view_index) >= model.bufferViews.size()) {
    return ParseError(what + " " + std::to_string(view_index) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(view_index)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return ParseError(what + " refers to a missing buffer");
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    return ParseError(what + " extends past the end of its buffer");
  }
  return data.data() + view.byteOffset;
}

}  // namespace eqmesh::gltf

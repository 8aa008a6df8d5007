#include "gltf/placeholder_indices.h"

#include <cstring>

#include <nlohmann/json.hpp>

#include "gltf/extension.h"

namespace eqmesh::gltf {
namespace {

using Json = nlohmann::json;

constexpr uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"

uint32_t LoadU32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void StoreU32(uint8_t* p, uint32_t v) { std::memcpy(p, &v, 4); }

bool IsGlb(const std::vector<uint8_t>& file) { return file.size() >= 4 && std::memcmp(file.data(), "glTF", 4) == 0; }

bool HasBufferView(const Json& accessors, const Json& index) {
  if (!index.is_number_unsigned() || !accessors.is_array()) return true;  // not ours to judge: tinygltf reports it
  const size_t i = index.get<size_t>();
  return i >= accessors.size() || !accessors[i].is_object() || accessors[i].contains("bufferView");
}

// Edits `doc` in place; true when anything was removed.
bool DetachFromJson(Json* doc, std::vector<DetachedIndices>* detached) {
  if (!doc->is_object() || !doc->contains("meshes") || !(*doc)["meshes"].is_array()) return false;
  const Json accessors = doc->value("accessors", Json::array());
  Json& meshes = (*doc)["meshes"];
  for (size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].is_object() || !meshes[m].contains("primitives") || !meshes[m]["primitives"].is_array()) continue;
    Json& primitives = meshes[m]["primitives"];
    for (size_t p = 0; p < primitives.size(); ++p) {
      Json& primitive = primitives[p];
      if (!primitive.is_object() || !primitive.contains("indices")) continue;
      const Json extensions = primitive.value("extensions", Json::object());
      if (!extensions.is_object() || !extensions.contains(kExtensionName)) continue;
      if (HasBufferView(accessors, primitive["indices"])) continue;
      detached->push_back({m, p, primitive["indices"].get<int>()});
      primitive.erase("indices");
    }
  }
  return !detached->empty();
}

StatusOr<std::vector<uint8_t>> RebuildGlb(const std::vector<uint8_t>& file, size_t json_end, const std::string& json) {
  std::string padded = json;
  while (padded.size() % 4 != 0) padded.push_back(' ');
  std::vector<uint8_t> out(file.begin(), file.begin() + 12);
  out.resize(20);
  StoreU32(out.data() + 12, static_cast<uint32_t>(padded.size()));
  StoreU32(out.data() + 16, kJsonChunk);
  out.insert(out.end(), padded.begin(), padded.end());
  out.insert(out.end(), file.begin() + static_cast<std::ptrdiff_t>(json_end), file.end());
  if (out.size() > 0xFFFFFFFFu) return ResourceLimit("GLB larger than 4 GiB");
  StoreU32(out.data() + 8, static_cast<uint32_t>(out.size()));
  return out;
}

StatusOr<std::vector<uint8_t>> DetachInGlb(const std::vector<uint8_t>& file, std::vector<DetachedIndices>* detached) {
  if (file.size() < 20 || LoadU32(file.data() + 16) != kJsonChunk) return file;  // tinygltf reports it
  const uint64_t json_size = LoadU32(file.data() + 12);
  if (20 + json_size > file.size()) return file;
  const Json doc = Json::parse(file.begin() + 20, file.begin() + static_cast<std::ptrdiff_t>(20 + json_size),
                               nullptr, false);
  if (doc.is_discarded()) return file;
  Json edited = doc;
  if (!DetachFromJson(&edited, detached)) return file;
  return RebuildGlb(file, static_cast<size_t>(20 + json_size), edited.dump());
}

}  // namespace

StatusOr<std::vector<uint8_t>> DetachPlaceholderIndices(const std::vector<uint8_t>& file,
                                                        std::vector<DetachedIndices>* detached) {
  detached->clear();
  if (IsGlb(file)) return DetachInGlb(file, detached);
  Json doc = Json::parse(file.begin(), file.end(), nullptr, false);
  if (doc.is_discarded() || !DetachFromJson(&doc, detached)) return file;
  const std::string text = doc.dump();
  return std::vector<uint8_t>(text.begin(), text.end());
}

Status ReattachPlaceholderIndices(const std::vector<DetachedIndices>& detached, tinygltf::Model* model) {
  // tinygltf drops primitives it cannot parse (one without "attributes", say), which
  // shifts the ones after it: a hostile file, reported as such.
  for (const DetachedIndices& d : detached) {
    tinygltf::Primitive* p = nullptr;
    if (d.mesh < model->meshes.size() && d.primitive < model->meshes[d.mesh].primitives.size()) {
      p = &model->meshes[d.mesh].primitives[d.primitive];
    }
    if (p == nullptr || p->indices >= 0 || p->extensions.count(kExtensionName) == 0) {
      return ParseError("mesh " + std::to_string(d.mesh) + " primitive " + std::to_string(d.primitive) +
                        ": primitive not loadable as written (a malformed primitive before it?)");
    }
    p->indices = d.accessor;
  }
  return Status::Ok();
}

}  // namespace eqmesh::gltf

#include "gltf/material_textures.h"

#include <cmath>
#include <map>

#include "core/status.h"
#include "gltf/buffer_layout.h"

namespace eqmesh::gltf {
namespace {

constexpr char kTextureTransform[] = "KHR_texture_transform";

double Number(const tinygltf::Value& object, const char* key, int element, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (element >= 0) {
    if (!v.IsArray() || v.ArrayLen() <= static_cast<size_t>(element)) return fallback;
    const tinygltf::Value& x = v.Get(element);
    return x.IsNumber() ? x.GetNumberAsDouble() : fallback;
  }
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// KHR_texture_transform as u' = m0 u + m1 v + m2, v' = m3 u + m4 v + m5: the
// extension's translation * rotation * scale, rotation [[c, s], [-s, c]].
void ApplyTransform(const tinygltf::Value& t, TextureSlot* slot) {
  if (!t.IsObject()) return;
  const double ox = Number(t, "offset", 0, 0.0), oy = Number(t, "offset", 1, 0.0);
  const double r = Number(t, "rotation", -1, 0.0);
  const double sx = Number(t, "scale", 0, 1.0), sy = Number(t, "scale", 1, 1.0);
  const double c = std::cos(r), s = std::sin(r);
  slot->uv_transform = {c * sx, s * sy, ox, -s * sx, c * sy, oy};
  if (t.Has("texCoord") && t.Get("texCoord").IsInt()) slot->tex_coord = t.Get("texCoord").GetNumberAsInt();
}

template <typename Info>
void AddCoreSlot(const std::string& key, const Info& info, std::vector<TextureSlot>* slots) {
  if (info.index < 0) return;
  TextureSlot slot;
  slot.key = key;
  slot.index = info.index;
  slot.tex_coord = info.texCoord;
  const auto t = info.extensions.find(kTextureTransform);
  if (t != info.extensions.end()) ApplyTransform(t->second, &slot);
  slots->push_back(slot);
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void AddExtensionSlots(const std::string& name, const tinygltf::Value& ext, std::vector<TextureSlot>* slots) {
  if (!ext.IsObject()) return;
  for (const std::string& key : ext.Keys()) {
    const tinygltf::Value& info = ext.Get(key);
    if (!EndsWith(key, "Texture") || !info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) continue;
    TextureSlot slot;
    slot.extension = name;
    slot.key = key;
    slot.index = info.Get("index").GetNumberAsInt();
    if (info.Has("texCoord") && info.Get("texCoord").IsInt()) slot.tex_coord = info.Get("texCoord").GetNumberAsInt();
    if (info.Has("extensions") && info.Get("extensions").Has(kTextureTransform)) {
      ApplyTransform(info.Get("extensions").Get(kTextureTransform), &slot);
    }
    slots->push_back(slot);
  }
}

// `retarget`: also sample TEXCOORD_0 without a transform; else only renumber.
template <typename Info>
void SetCore(Info* info, int texture, bool retarget) {
  info->index = texture;
  if (!retarget) return;
  info->texCoord = 0;
  info->extensions.erase(kTextureTransform);
}

tinygltf::Value SetInfo(const tinygltf::Value& info, int texture, bool retarget) {
  tinygltf::Value::Object object = info.Get<tinygltf::Value::Object>();
  object["index"] = tinygltf::Value(texture);
  if (!retarget) return tinygltf::Value(std::move(object));
  object.erase("texCoord");
  const auto ext = object.find("extensions");
  if (ext != object.end() && ext->second.IsObject()) {
    tinygltf::Value::Object extensions = ext->second.Get<tinygltf::Value::Object>();
    extensions.erase(kTextureTransform);
    if (extensions.empty()) {
      object.erase("extensions");
    } else {
      object["extensions"] = tinygltf::Value(std::move(extensions));
    }
  }
  return tinygltf::Value(std::move(object));
}

void SetSlot(const TextureSlot& slot, int texture, bool retarget, tinygltf::Material* m) {
  if (slot.extension.empty()) {
    if (slot.key == "baseColorTexture") SetCore(&m->pbrMetallicRoughness.baseColorTexture, texture, retarget);
    if (slot.key == "metallicRoughnessTexture") SetCore(&m->pbrMetallicRoughness.metallicRoughnessTexture, texture, retarget);
    if (slot.key == "occlusionTexture") SetCore(&m->occlusionTexture, texture, retarget);
    if (slot.key == "emissiveTexture") SetCore(&m->emissiveTexture, texture, retarget);
    if (slot.key == "normalTexture") SetCore(&m->normalTexture, texture, retarget);
    return;
  }
  tinygltf::Value::Object ext = m->extensions.at(slot.extension).Get<tinygltf::Value::Object>();
  ext[slot.key] = SetInfo(ext[slot.key], texture, retarget);
  m->extensions[slot.extension] = tinygltf::Value(std::move(ext));
}

// Keeps the entries of `used`, renumbered in order; returns old -> new.
template <typename T>
std::map<int, int> KeepUsed(std::vector<T>* items, const std::set<int>& used) {
  std::map<int, int> remap;
  std::vector<T> kept;
  for (int i = 0; i < static_cast<int>(items->size()); ++i) {
    if (used.count(i) == 0) continue;
    remap[i] = static_cast<int>(kept.size());
    kept.push_back(std::move((*items)[static_cast<size_t>(i)]));
  }
  items->swap(kept);
  return remap;
}

void DropUnusedMaterials(tinygltf::Model* model) {
  std::set<int> used;
  for (const tinygltf::Mesh& m : model->meshes) {
    for (const tinygltf::Primitive& p : m.primitives) {
      if (p.material >= 0) used.insert(p.material);
    }
  }
  const std::map<int, int> remap = KeepUsed(&model->materials, used);
  for (tinygltf::Mesh& m : model->meshes) {
    for (tinygltf::Primitive& p : m.primitives) {
      if (p.material >= 0) p.material = remap.count(p.material) ? remap.at(p.material) : -1;
    }
  }
}

void DropUnusedTextures(tinygltf::Model* model) {
  std::set<int> used;
  for (const tinygltf::Material& m : model->materials) {
    for (const TextureSlot& s : UsedTextureSlots(m)) used.insert(s.index);
  }
  const std::map<int, int> remap = KeepUsed(&model->textures, used);
  for (tinygltf::Material& m : model->materials) {
    for (const TextureSlot& s : UsedTextureSlots(m)) {
      if (remap.count(s.index)) SetSlot(s, remap.at(s.index), false, &m);
    }
  }
}

void DropUnusedImages(tinygltf::Model* model, std::set<int>* stale_views) {
  std::set<int> used;
  for (const tinygltf::Texture& t : model->textures) {
    if (!t.extensions.empty()) return;
    if (t.source >= 0) used.insert(t.source);
  }
  for (int i = 0; i < static_cast<int>(model->images.size()); ++i) {
    const int view = model->images[static_cast<size_t>(i)].bufferView;
    if (used.count(i) == 0 && view >= 0) stale_views->insert(view);
  }
  const std::map<int, int> remap = KeepUsed(&model->images, used);
  for (tinygltf::Texture& t : model->textures) {
    if (t.source >= 0) t.source = remap.count(t.source) ? remap.at(t.source) : -1;
  }
}

}  // namespace

bool TextureSlot::IsNormalMap() const { return key == "normalTexture" || EndsWith(key, "NormalTexture"); }

std::string TextureSlot::Name() const { return extension.empty() ? key : extension + "." + key; }

std::vector<TextureSlot> UsedTextureSlots(const tinygltf::Material& m) {
  std::vector<TextureSlot> slots;
  AddCoreSlot("baseColorTexture", m.pbrMetallicRoughness.baseColorTexture, &slots);
  AddCoreSlot("metallicRoughnessTexture", m.pbrMetallicRoughness.metallicRoughnessTexture, &slots);
  AddCoreSlot("occlusionTexture", m.occlusionTexture, &slots);
  AddCoreSlot("emissiveTexture", m.emissiveTexture, &slots);
  AddCoreSlot("normalTexture", m.normalTexture, &slots);
  for (const auto& [name, value] : m.extensions) AddExtensionSlots(name, value, &slots);
  return slots;
}

void RetargetSlot(const TextureSlot& slot, int texture, tinygltf::Material* m) { SetSlot(slot, texture, true, m); }

StatusOr<std::vector<uint8_t>> ImageBytes(const tinygltf::Model& model, int i) {
  if (i < 0 || static_cast<size_t>(i) >= model.images.size()) return ParseError("image " + std::to_string(i) + " does not exist");
  const tinygltf::Image& image = model.images[static_cast<size_t>(i)];
  if (image.bufferView < 0) {
    if (image.image.empty()) return ParseError("image " + std::to_string(i) + " has no data");
    return std::vector<uint8_t>(image.image.begin(), image.image.end());
  }
  EQMESH_ASSIGN_OR_RETURN(const uint8_t* first,
                          BufferViewData(model, image.bufferView, "image " + std::to_string(i) + "'s bufferView"));
  return std::vector<uint8_t>(first, first + model.bufferViews[static_cast<size_t>(image.bufferView)].byteLength);
}

void RemoveUnusedMaterials(tinygltf::Model* model, std::set<int>* stale_views) {
  DropUnusedMaterials(model);
  DropUnusedTextures(model);
  DropUnusedImages(model, stale_views);
}

}  // namespace eqmesh::gltf

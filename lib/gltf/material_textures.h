// The texture slots of a glTF material, read and rewritten uniformly: the core
// ones (pbrMetallicRoughness base colour and metallic-roughness, occlusion,
// emissive, normal) and every textureInfo a material extension holds at its top
// level (KHR_materials_pbrSpecularGlossiness' diffuseTexture, clearcoat's, ...:
// an object with an integer "index" under a key ending in "Texture"). Also the
// clean-up once compressed primitives sample new atlas textures.
#pragma once

#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"

namespace eqmesh::gltf {

struct TextureSlot {
  std::string extension;  // empty for a core slot
  std::string key;        // "baseColorTexture", "diffuseTexture", ...
  int index = -1;
  int tex_coord = 0;               // KHR_texture_transform's texCoord applied
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};  // see SlotUvTransform
  bool IsNormalMap() const;        // its values are tangent-space normals
  std::string Name() const;        // "baseColorTexture" or "EXT.key"
};

// The slots of `material` that sample a texture, in a fixed order (core slots,
// then extensions by name, keys by name).
std::vector<TextureSlot> UsedTextureSlots(const tinygltf::Material& material);

// Points `slot` of `material` at texture `texture`, sampled through TEXCOORD_0
// with no KHR_texture_transform.
void RetargetSlot(const TextureSlot& slot, int texture, tinygltf::Material* material);

// The file bytes of image i (its buffer view, or the bytes the reader kept for
// a URI), bounds-checked.
StatusOr<std::vector<uint8_t>> ImageBytes(const tinygltf::Model& model, int i);

// Drops materials no primitive uses, textures no material slot uses and images no
// texture uses, renumbering every reference; a texture with extensions (another
// image source) keeps every image. The dropped images' buffer views are added to
// `stale_views`.
void RemoveUnusedMaterials(tinygltf::Model* model, std::set<int>* stale_views);

}  // namespace eqmesh::gltf

#include "gltf/surface_color.h"

#include <algorithm>
#include <map>

#include "gltf/accessor_io.h"
#include "gltf/gltf_loader.h"
#include "gltf/material_textures.h"
#include "texture/image_codec.h"
#include "texture/texture_transfer.h"

namespace eqmesh::gltf {
namespace {

// How one primitive is coloured; vertex indices are the flattened mesh's minus
// first_vertex.
struct PrimitiveColor {
  uint32_t first_vertex = 0;
  std::array<double, 3> factor{1, 1, 1};
  int image = -1;  // into ColorData::images
  int wrap_s = 10497, wrap_t = 10497;
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};
  std::vector<std::array<double, 2>> texcoords;  // empty without a texture
  std::vector<std::array<double, 3>> colors;     // COLOR_0, empty without
};

struct ColorData {
  std::vector<Face> faces;
  std::vector<uint32_t> face_primitive;
  std::vector<PrimitiveColor> primitives;
  std::vector<texture::Image> images;
  std::map<int, int> image_of_gltf_image;
};

// The slot that carries the base colour: pbrMetallicRoughness' baseColorTexture,
// else the specular-glossiness diffuse texture.
const TextureSlot* BaseColorSlot(const std::vector<TextureSlot>& slots) {
  for (const TextureSlot& s : slots) {
    if (s.extension.empty() && s.key == "baseColorTexture") return &s;
  }
  for (const TextureSlot& s : slots) {
    if (s.extension == "KHR_materials_pbrSpecularGlossiness" && s.key == "diffuseTexture") return &s;
  }
  return nullptr;
}

std::array<double, 3> Factor(const tinygltf::Material& m) {
  const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
  if (f.size() >= 3) return {f[0], f[1], f[2]};
  return {1, 1, 1};
}

StatusOr<int> CachedImage(const tinygltf::Model& model, int gltf_image, ColorData* data) {
  const auto it = data->image_of_gltf_image.find(gltf_image);
  if (it != data->image_of_gltf_image.end()) return it->second;
  EQMESH_ASSIGN_OR_RETURN(const std::vector<uint8_t> bytes, ImageBytes(model, gltf_image));
  EQMESH_ASSIGN_OR_RETURN(texture::Image image, texture::DecodeImage(bytes.data(), bytes.size()));
  data->images.push_back(std::move(image));
  const int index = static_cast<int>(data->images.size()) - 1;
  data->image_of_gltf_image[gltf_image] = index;
  return index;
}

Status ReadTexture(const tinygltf::Model& model, const tinygltf::Primitive& p, const TextureSlot& slot,
                   PrimitiveColor* out, ColorData* data) {
  if (slot.index < 0 || static_cast<size_t>(slot.index) >= model.textures.size()) {
    return ParseError("texture " + std::to_string(slot.index) + " does not exist");
  }
  const tinygltf::Texture& texture = model.textures[static_cast<size_t>(slot.index)];
  const auto uv = p.attributes.find("TEXCOORD_" + std::to_string(slot.tex_coord));
  if (uv == p.attributes.end() || texture.source < 0) return Status::Ok();  // nothing to sample: factor only
  EQMESH_ASSIGN_OR_RETURN(out->texcoords, ReadTexcoordAccessor(model, uv->second, uv->first));
  EQMESH_ASSIGN_OR_RETURN(out->image, CachedImage(model, texture.source, data));
  if (texture.sampler >= 0 && static_cast<size_t>(texture.sampler) < model.samplers.size()) {
    out->wrap_s = model.samplers[static_cast<size_t>(texture.sampler)].wrapS;
    out->wrap_t = model.samplers[static_cast<size_t>(texture.sampler)].wrapT;
  }
  out->uv_transform = slot.uv_transform;
  return Status::Ok();
}

Status ReadPrimitiveColor(const tinygltf::Model& model, const tinygltf::Primitive& p, size_t vertices,
                          PrimitiveColor* out, ColorData* data) {
  if (p.material >= 0 && static_cast<size_t>(p.material) < model.materials.size()) {
    const tinygltf::Material& material = model.materials[static_cast<size_t>(p.material)];
    out->factor = Factor(material);
    const std::vector<TextureSlot> slots = UsedTextureSlots(material);
    const TextureSlot* slot = BaseColorSlot(slots);
    if (slot != nullptr) EQMESH_RETURN_IF_ERROR(ReadTexture(model, p, *slot, out, data));
  }
  const auto color = p.attributes.find("COLOR_0");
  if (color != p.attributes.end()) {
    EQMESH_ASSIGN_OR_RETURN(out->colors, ReadColorAccessor(model, color->second, "COLOR_0"));
  }
  if ((!out->texcoords.empty() && out->texcoords.size() != vertices) ||
      (!out->colors.empty() && out->colors.size() != vertices)) {
    return ParseError("TEXCOORD or COLOR_0 count differs from POSITION's");
  }
  return Status::Ok();
}

std::array<double, 3> ColorAt(const ColorData& data, uint32_t face, const std::array<double, 3>& b) {
  const PrimitiveColor& p = data.primitives[data.face_primitive[face]];
  std::array<double, 3> c{255.0 * p.factor[0], 255.0 * p.factor[1], 255.0 * p.factor[2]};
  const Face& f = data.faces[face];
  if (p.image >= 0) {
    double u = 0, v = 0;
    for (size_t k = 0; k < 3; ++k) {
      u += b[k] * p.texcoords[f[k] - p.first_vertex][0];
      v += b[k] * p.texcoords[f[k] - p.first_vertex][1];
    }
    const texture::Image& image = data.images[static_cast<size_t>(p.image)];
    const auto& m = p.uv_transform;
    texture::SourceTexture source{&image, p.wrap_s, p.wrap_t, m};
    float texel[4] = {0, 0, 0, 0};
    texture::SampleBilinear(source, m[0] * u + m[1] * v + m[2], m[3] * u + m[4] * v + m[5], texel);
    const bool gray = image.channels < 3;
    for (size_t k = 0; k < 3; ++k) c[k] *= texel[gray ? 0 : k] / 255.0;
  }
  if (!p.colors.empty()) {
    for (size_t k = 0; k < 3; ++k) {
      double vc = 0;
      for (size_t j = 0; j < 3; ++j) vc += b[j] * p.colors[f[j] - p.first_vertex][k];
      c[k] *= vc;
    }
  }
  return c;
}

}  // namespace

StatusOr<ColoredScene> FlattenWithColor(const tinygltf::Model& model) {
  auto data = std::make_shared<ColorData>();
  ColoredScene scene;
  uint64_t budget = FlattenBudget(model);
  const PrimitiveVisitor append = [&](const tinygltf::Primitive& primitive, const std::string& label,
                                     const Eigen::Affine3d& world) -> Status {
    auto part = ReadTrianglePrimitive(model, primitive);
    if (!part.ok()) return part.status().WithContext(label);
    EQMESH_RETURN_IF_ERROR(SpendBudget(part->positions.size() + part->faces.size(), &budget));
    PrimitiveColor color;
    color.first_vertex = static_cast<uint32_t>(scene.mesh.positions.size());
    EQMESH_RETURN_IF_ERROR(
        ReadPrimitiveColor(model, primitive, part->positions.size(), &color, data.get()).WithContext(label));
    scene.varies = scene.varies || color.image >= 0 || !color.colors.empty();
    data->primitives.push_back(std::move(color));
    data->face_primitive.insert(data->face_primitive.end(), part->faces.size(),
                                static_cast<uint32_t>(data->primitives.size() - 1));
    AppendTransformed(*part, world, &scene.mesh);
    return Status::Ok();
  };
  EQMESH_RETURN_IF_ERROR(VisitScenePrimitives(model, append));
  if (scene.mesh.faces.empty()) return InvalidMesh("the scene has no triangles");
  data->faces = scene.mesh.faces;
  const ColorData* raw = data.get();
  scene.color = [raw](uint32_t face, const std::array<double, 3>& b) { return ColorAt(*raw, face, b); };
  scene.data = data;
  return scene;
}

}  // namespace eqmesh::gltf

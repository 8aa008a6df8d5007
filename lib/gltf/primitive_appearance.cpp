#include "gltf/primitive_appearance.h"

#include <algorithm>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "gltf/gltf_io.h"
#include "gltf/material_textures.h"

namespace eqmesh::gltf {
namespace {

constexpr size_t kNoSlot = static_cast<size_t>(-1);

bool IsBaseColor(const TextureSlot& slot) {
  return (slot.extension.empty() && slot.key == "baseColorTexture") ||
         (slot.extension == "KHR_materials_pbrSpecularGlossiness" && slot.key == "diffuseTexture");
}

// One atlas image to paint: from the first slot that samples it (kNoSlot: from
// COLOR_0 alone), times COLOR_0 when it is the base colour and the plan bakes it.
struct Job {
  size_t first_slot = kNoSlot;
  bool base_color = false;
};

// Slots sampling the same texture the same way (and, with COLOR_0 baked, in the
// same role) share one job; job_of_slot[i] names slot i's.
std::vector<Job> PlanJobs(const std::vector<TextureSlot>& slots, const AppearancePlan& plan,
                          std::vector<size_t>* job_of_slot) {
  std::vector<Job> jobs;
  job_of_slot->assign(slots.size(), 0);
  bool has_base_color = false;
  for (size_t i = 0; i < slots.size(); ++i) {
    const bool base = plan.vertex_colors && IsBaseColor(slots[i]);
    has_base_color = has_base_color || IsBaseColor(slots[i]);
    size_t k = 0;
    while (k < jobs.size() && !(slots[jobs[k].first_slot].index == slots[i].index &&
                                slots[jobs[k].first_slot].uv_transform == slots[i].uv_transform &&
                                jobs[k].base_color == base)) {
      ++k;
    }
    if (k == jobs.size()) jobs.push_back({i, base});
    (*job_of_slot)[i] = k;
  }
  if (plan.vertex_colors && !has_base_color) jobs.push_back({kNoSlot, true});
  return jobs;
}

const tinygltf::Material& MaterialOf(const tinygltf::Model& model, const tinygltf::Primitive& p) {
  static const tinygltf::Material kDefault;  // glTF's default material (tinygltf's defaults match it)
  return p.material >= 0 && static_cast<size_t>(p.material) < model.materials.size()
             ? model.materials[static_cast<size_t>(p.material)]
             : kDefault;
}

std::string VertexColorDisqualification(const tinygltf::Model& model, const tinygltf::Primitive& p) {
  const auto color = p.attributes.find("COLOR_0");
  if (color == p.attributes.end()) return "";
  if (color->second < 0 || static_cast<size_t>(color->second) >= model.accessors.size()) {
    return "COLOR_0 names a missing accessor";
  }
  const bool has_alpha = model.accessors[static_cast<size_t>(color->second)].type == TINYGLTF_TYPE_VEC4;
  const std::string& mode = MaterialOf(model, p).alphaMode;
  if (has_alpha && !mode.empty() && mode != "OPAQUE") {
    return "COLOR_0 carries alpha under alphaMode " + mode + ", which eqmesh does not bake yet";
  }
  return "";
}

Status ReadJob(const tinygltf::Model& model, const tinygltf::Material& material, const TextureSlot& slot,
               TextureJob* job) {
  const tinygltf::Texture& texture = model.textures[static_cast<size_t>(slot.index)];
  job->normal_map = slot.IsNormalMap();
  if (job->normal_map) job->normal_scale = material.normalTexture.scale;
  EQMESH_ASSIGN_OR_RETURN(job->encoded, ImageBytes(model, texture.source));
  if (texture.sampler >= 0 && static_cast<size_t>(texture.sampler) < model.samplers.size()) {
    job->wrap_s = model.samplers[static_cast<size_t>(texture.sampler)].wrapS;
    job->wrap_t = model.samplers[static_cast<size_t>(texture.sampler)].wrapT;
  }
  job->uv_transform = slot.uv_transform;
  return Status::Ok();
}

// NORMAL and TANGENT as given (a normal map was authored against them).
Status ReadFrames(const tinygltf::Model& model, const tinygltf::Primitive& p, PrimitiveGeometry* out) {
  const size_t vertices = out->mesh.positions.size();
  const auto normal = p.attributes.find("NORMAL");
  if (normal != p.attributes.end()) {
    EQMESH_ASSIGN_OR_RETURN(out->normals, ReadVec3Accessor(model, normal->second, "NORMAL"));
    if (out->normals.size() != vertices) return ParseError("NORMAL and POSITION counts differ");
    for (Vec3& n : out->normals) n = n.squaredNorm() > 0 ? n.normalized() : Vec3::UnitZ();
  }
  const auto tangent = p.attributes.find("TANGENT");
  if (tangent != p.attributes.end()) {
    EQMESH_ASSIGN_OR_RETURN(out->tangents, ReadTangentAccessor(model, tangent->second));
    if (out->tangents.size() != vertices) return ParseError("TANGENT and POSITION counts differ");
  }
  return Status::Ok();
}

// A new image holding `bytes` and a texture sampling it (with `like`'s sampler
// when given); returns the texture's index.
int AddTexture(const std::vector<uint8_t>& bytes, const tinygltf::Texture* like, tinygltf::Model* model) {
  tinygltf::Image image;
  if (like != nullptr) image = model->images[static_cast<size_t>(like->source)];
  image.bufferView = AppendBufferView(model, bytes.data(), bytes.size(), 0);
  image.image.clear();
  image.uri.clear();
  if (image.mimeType.empty() || like == nullptr) image.mimeType = GuessMimeType(bytes);
  model->images.push_back(image);
  tinygltf::Texture texture = like != nullptr ? *like : tinygltf::Texture();
  texture.source = static_cast<int>(model->images.size()) - 1;
  model->textures.push_back(texture);
  return static_cast<int>(model->textures.size()) - 1;
}

}  // namespace

std::string AppearanceDisqualification(const tinygltf::Model& model, const tinygltf::Primitive& p,
                                       AppearancePlan* plan) {
  *plan = AppearancePlan();
  const std::string colors = VertexColorDisqualification(model, p);
  if (!colors.empty()) return colors;
  plan->vertex_colors = p.attributes.count("COLOR_0") > 0;
  const std::string m = "material " + std::to_string(p.material);
  for (const TextureSlot& slot : UsedTextureSlots(MaterialOf(model, p))) {
    if (slot.IsNormalMap() && !slot.extension.empty()) {
      return m + " has a normal map in " + slot.Name() + ", which eqmesh does not re-express yet";
    }
    if (slot.index < 0 || static_cast<size_t>(slot.index) >= model.textures.size()) return m + " names a missing texture";
    const tinygltf::Texture& texture = model.textures[static_cast<size_t>(slot.index)];
    if (!texture.extensions.empty() || texture.source < 0 ||
        static_cast<size_t>(texture.source) >= model.images.size()) {
      return m + " samples texture " + std::to_string(slot.index) + ", whose image is not a plain PNG or JPEG source";
    }
    if (plan->tex_coord >= 0 && slot.tex_coord != plan->tex_coord) return m + " samples two TEXCOORD sets";
    plan->tex_coord = slot.tex_coord;
  }
  if (plan->tex_coord >= 0 && p.attributes.count("TEXCOORD_" + std::to_string(plan->tex_coord)) == 0) {
    return m + " samples TEXCOORD_" + std::to_string(plan->tex_coord) + ", which the primitive lacks";
  }
  return "";
}

bool CarriedByAtlas(const AppearancePlan& plan, const std::string& semantic) {
  return (plan.tex_coord >= 0 && semantic == "TEXCOORD_" + std::to_string(plan.tex_coord)) ||
         (plan.vertex_colors && semantic == "COLOR_0") || (plan.tex_coord >= 0 && semantic == "TANGENT");
}

Status ReadAppearance(const tinygltf::Model& model, const tinygltf::Primitive& p, const AppearancePlan& plan,
                      PrimitiveGeometry* out) {
  const size_t vertices = out->mesh.positions.size();
  if (plan.tex_coord >= 0) {
    const std::string name = "TEXCOORD_" + std::to_string(plan.tex_coord);
    EQMESH_ASSIGN_OR_RETURN(out->texcoords, ReadTexcoordAccessor(model, p.attributes.at(name), name));
    if (out->texcoords.size() != vertices) return ParseError(name + " and POSITION counts differ");
  }
  if (plan.vertex_colors) {
    EQMESH_ASSIGN_OR_RETURN(out->colors, ReadColorAccessor(model, p.attributes.at("COLOR_0"), "COLOR_0"));
    if (out->colors.size() != vertices) return ParseError("COLOR_0 and POSITION counts differ");
  }
  const std::vector<TextureSlot> slots = UsedTextureSlots(MaterialOf(model, p));
  const bool normal_map = std::any_of(slots.begin(), slots.end(), [](const TextureSlot& s) { return s.IsNormalMap(); });
  if (normal_map) EQMESH_RETURN_IF_ERROR(ReadFrames(model, p, out));
  std::vector<size_t> job_of_slot;
  for (const Job& planned : PlanJobs(slots, plan, &job_of_slot)) {
    TextureJob job;
    job.times_vertex_colors = planned.base_color && plan.vertex_colors;
    if (planned.first_slot != kNoSlot) {
      EQMESH_RETURN_IF_ERROR(ReadJob(model, MaterialOf(model, p), slots[planned.first_slot], &job));
    }
    out->textures.push_back(std::move(job));
  }
  return Status::Ok();
}

void ReplaceAppearance(const AppearancePlan& plan, const CompressedGeometry& geometry, tinygltf::Model* model,
                       tinygltf::Primitive* p) {
  tinygltf::Material material = MaterialOf(*model, *p);
  const std::vector<TextureSlot> slots = UsedTextureSlots(material);
  std::vector<size_t> job_of_slot;
  const std::vector<Job> jobs = PlanJobs(slots, plan, &job_of_slot);
  std::vector<int> new_texture(jobs.size());
  for (size_t k = 0; k < jobs.size(); ++k) {
    // A copy: AddTexture grows model->textures.
    const tinygltf::Texture like = jobs[k].first_slot != kNoSlot
                                       ? model->textures[static_cast<size_t>(slots[jobs[k].first_slot].index)]
                                       : tinygltf::Texture();
    new_texture[k] = AddTexture(geometry.textures[k], jobs[k].first_slot != kNoSlot ? &like : nullptr, model);
  }
  for (size_t i = 0; i < slots.size(); ++i) RetargetSlot(slots[i], new_texture[job_of_slot[i]], &material);
  if (material.normalTexture.index >= 0) material.normalTexture.scale = 1.0;  // baked into the new map
  if (!jobs.empty() && jobs.back().first_slot == kNoSlot) {
    material.pbrMetallicRoughness.baseColorTexture.index = new_texture.back();
    material.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
  }
  model->materials.push_back(material);
  p->material = static_cast<int>(model->materials.size()) - 1;
}

}  // namespace eqmesh::gltf

#include "gltf/compress_primitives.h"

#include <numeric>
#include <set>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "gltf/extension.h"
#include "gltf/material_textures.h"

namespace eqmesh::gltf {
namespace {

// Empty when the textures of primitive p's material can move to a new atlas, else
// why not; *tex_coord receives the TEXCOORD set they sample (-1: none).
std::string TextureDisqualification(const tinygltf::Model& model, const tinygltf::Primitive& p, int* tex_coord) {
  *tex_coord = -1;
  if (p.material < 0 || static_cast<size_t>(p.material) >= model.materials.size()) return "";
  const std::string m = "material " + std::to_string(p.material);
  for (const TextureSlot& slot : UsedTextureSlots(model.materials[static_cast<size_t>(p.material)])) {
    if (slot.IsNormalMap()) return m + " has a normal map (" + slot.Name() + "), which eqmesh does not re-express yet";
    if (slot.index < 0 || static_cast<size_t>(slot.index) >= model.textures.size()) return m + " names a missing texture";
    const tinygltf::Texture& texture = model.textures[static_cast<size_t>(slot.index)];
    if (!texture.extensions.empty() || texture.source < 0 ||
        static_cast<size_t>(texture.source) >= model.images.size()) {
      return m + " samples texture " + std::to_string(slot.index) + ", whose image is not a plain PNG or JPEG source";
    }
    if (*tex_coord >= 0 && slot.tex_coord != *tex_coord) return m + " samples two TEXCOORD sets";
    *tex_coord = slot.tex_coord;
  }
  if (*tex_coord >= 0 && p.attributes.count("TEXCOORD_" + std::to_string(*tex_coord)) == 0) {
    return m + " samples TEXCOORD_" + std::to_string(*tex_coord) + ", which the primitive lacks";
  }
  return "";
}

// Empty when the primitive can be compressed, else why not.
std::string Disqualification(const tinygltf::Model& model, const tinygltf::Primitive& p,
                             const ContainerOptions& options, int* tex_coord) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) return "mode " + std::to_string(p.mode) + " is not TRIANGLES";
  for (const auto& [name, value] : p.extensions) {
    if (name == kExtensionName || name == "KHR_draco_mesh_compression") return "already compressed with " + name;
  }
  if (!p.targets.empty()) return "has morph targets, which remeshing cannot carry";
  const std::string textures = TextureDisqualification(model, p, tex_coord);
  if (!textures.empty()) return textures;
  if (p.attributes.count("POSITION") == 0) return "has no POSITION";
  const std::string sampled = *tex_coord >= 0 ? "TEXCOORD_" + std::to_string(*tex_coord) : "";
  if (!options.drop_other_attributes) {
    for (const auto& [semantic, accessor] : p.attributes) {
      if (semantic != "POSITION" && semantic != "NORMAL" && semantic != sampled) {
        return "has attribute " + semantic + ", which remeshing cannot carry (drop_other_attributes drops it)";
      }
    }
  }
  return "";
}

// Slots sampling the same texture the same way share one painted atlas image:
// job k of the result is painted once and every slot mapped to k samples it.
std::vector<size_t> JobOfEachSlot(const std::vector<TextureSlot>& slots, std::vector<size_t>* first_slot_of_job) {
  std::vector<size_t> job(slots.size());
  first_slot_of_job->clear();
  for (size_t i = 0; i < slots.size(); ++i) {
    job[i] = first_slot_of_job->size();
    for (size_t k = 0; k < first_slot_of_job->size(); ++k) {
      const TextureSlot& other = slots[(*first_slot_of_job)[k]];
      if (other.index == slots[i].index && other.uv_transform == slots[i].uv_transform) job[i] = k;
    }
    if (job[i] == first_slot_of_job->size()) first_slot_of_job->push_back(i);
  }
  return job;
}

// What the compressor needs to know of a textured primitive's material.
Status ReadTextures(const tinygltf::Model& model, const tinygltf::Primitive& p, int tex_coord,
                    PrimitiveGeometry* out) {
  if (tex_coord < 0) return Status::Ok();
  EQMESH_ASSIGN_OR_RETURN(out->texcoords, ReadTexcoordAccessor(model, p.attributes.at("TEXCOORD_" + std::to_string(tex_coord)),
                                                               "TEXCOORD_" + std::to_string(tex_coord)));
  if (out->texcoords.size() != out->mesh.positions.size()) return ParseError("TEXCOORD and POSITION counts differ");
  const std::vector<TextureSlot> slots = UsedTextureSlots(model.materials[static_cast<size_t>(p.material)]);
  std::vector<size_t> first_slots;
  JobOfEachSlot(slots, &first_slots);
  for (size_t first : first_slots) {
    const TextureSlot& slot = slots[first];
    const tinygltf::Texture& texture = model.textures[static_cast<size_t>(slot.index)];
    TextureJob job;
    EQMESH_ASSIGN_OR_RETURN(job.encoded, ImageBytes(model, texture.source));
    if (texture.sampler >= 0 && static_cast<size_t>(texture.sampler) < model.samplers.size()) {
      job.wrap_s = model.samplers[static_cast<size_t>(texture.sampler)].wrapS;
      job.wrap_t = model.samplers[static_cast<size_t>(texture.sampler)].wrapT;
    }
    job.uv_transform = slot.uv_transform;
    out->textures.push_back(std::move(job));
  }
  return Status::Ok();
}

class PrimitiveCompressor {
 public:
  PrimitiveCompressor(tinygltf::Model* model, const GeometryCompressor& compressor, const ContainerOptions& options)
      : model_(model), compressor_(compressor), options_(options) {}

  PrimitiveOutcome Compress(size_t mesh_index, size_t primitive_index);
  const std::set<int>& old_accessors() const { return old_accessors_; }
  const std::set<int>& old_views() const { return old_views_; }
  std::set<int>* mutable_old_views() { return &old_views_; }
  bool textures_replaced() const { return textures_replaced_; }

 private:
  Status Replace(tinygltf::Primitive* p, const CompressedGeometry& geometry);
  void ReplaceTextures(tinygltf::Primitive* p, const CompressedGeometry& geometry);
  void RememberOldData(const tinygltf::Primitive& p);
  int NewAccessor() {
    model_->accessors.emplace_back();
    return static_cast<int>(model_->accessors.size()) - 1;
  }

  tinygltf::Model* model_;
  const GeometryCompressor& compressor_;
  const ContainerOptions& options_;
  std::set<int> old_accessors_;
  std::set<int> old_views_;
  bool textures_replaced_ = false;
};

void PrimitiveCompressor::RememberOldData(const tinygltf::Primitive& p) {
  std::vector<int> accessors;
  for (const auto& [semantic, index] : p.attributes) accessors.push_back(index);
  if (p.indices >= 0) accessors.push_back(p.indices);
  for (int a : accessors) {
    if (a < 0 || static_cast<size_t>(a) >= model_->accessors.size()) continue;
    old_accessors_.insert(a);
    const tinygltf::Accessor& accessor = model_->accessors[static_cast<size_t>(a)];
    for (int view : {accessor.bufferView, accessor.sparse.indices.bufferView, accessor.sparse.values.bufferView}) {
      if (view >= 0) old_views_.insert(view);
    }
  }
}

Status PrimitiveCompressor::Replace(tinygltf::Primitive* p, const CompressedGeometry& geometry) {
  const uint64_t total = std::accumulate(geometry.chunk_lengths.begin(), geometry.chunk_lengths.end(), uint64_t{0});
  if (geometry.chunk_lengths.empty() || total != geometry.stream.size()) {
    return InternalError("chunk lengths do not add up to the stream size");
  }
  const bool textured = !geometry.texcoords.empty();
  const GeometryAccessors accessors{NewAccessor(), NewAccessor(), NewAccessor(), textured ? NewAccessor() : -1};
  const GeometryData data{&geometry.decoded, geometry.normals.empty() ? nullptr : &geometry.normals,
                          textured ? &geometry.texcoords : nullptr};
  EQMESH_RETURN_IF_ERROR(WriteGeometry(model_, data, accessors, options_.fallback).status());
  NormalMeshExtension ext;
  ext.buffer_view = AppendBufferView(model_, geometry.stream.data(), geometry.stream.size(), 0);
  ext.levels = static_cast<int>(geometry.chunk_lengths.size()) - 1;
  ext.level_ranges = RangesFromLengths(geometry.chunk_lengths);
  ext.position_accessor = accessors.position;
  ext.normal_accessor = accessors.normal;
  ext.texcoord_accessor = accessors.texcoord;
  RememberOldData(*p);
  // NORMAL is always declared: without it glTF asks for flat shading, which shows
  // every facet of a remeshed scan.
  p->attributes = {{"POSITION", accessors.position}, {"NORMAL", accessors.normal}};
  if (textured) {
    p->attributes["TEXCOORD_0"] = accessors.texcoord;
    ReplaceTextures(p, geometry);
  }
  p->indices = accessors.indices;
  p->mode = TINYGLTF_MODE_TRIANGLES;
  p->extensions[kExtensionName] = ExtensionToValue(ext);
  return Status::Ok();
}

// The primitive gets a copy of its material whose slots sample the new atlas
// images (TEXCOORD_0, no transform), each a new texture with the old sampler.
void PrimitiveCompressor::ReplaceTextures(tinygltf::Primitive* p, const CompressedGeometry& geometry) {
  tinygltf::Material material = model_->materials[static_cast<size_t>(p->material)];
  const std::vector<TextureSlot> slots = UsedTextureSlots(material);
  std::vector<size_t> first_slots;
  const std::vector<size_t> job = JobOfEachSlot(slots, &first_slots);
  std::vector<int> new_texture(first_slots.size());
  for (size_t k = 0; k < first_slots.size(); ++k) {
    const tinygltf::Texture old_texture = model_->textures[static_cast<size_t>(slots[first_slots[k]].index)];
    tinygltf::Image image = model_->images[static_cast<size_t>(old_texture.source)];
    image.bufferView = AppendBufferView(model_, geometry.textures[k].data(), geometry.textures[k].size(), 0);
    image.image.clear();
    image.uri.clear();
    model_->images.push_back(image);
    tinygltf::Texture texture = old_texture;
    texture.source = static_cast<int>(model_->images.size()) - 1;
    model_->textures.push_back(texture);
    new_texture[k] = static_cast<int>(model_->textures.size()) - 1;
  }
  for (size_t i = 0; i < slots.size(); ++i) RetargetSlot(slots[i], new_texture[job[i]], &material);
  model_->materials.push_back(material);
  p->material = static_cast<int>(model_->materials.size()) - 1;
  textures_replaced_ = true;
}

PrimitiveOutcome PrimitiveCompressor::Compress(size_t mesh_index, size_t primitive_index) {
  tinygltf::Primitive& p = model_->meshes[mesh_index].primitives[primitive_index];
  PrimitiveOutcome out;
  out.mesh = static_cast<int>(mesh_index);
  out.primitive = static_cast<int>(primitive_index);
  int tex_coord = -1;
  out.reason = Disqualification(*model_, p, options_, &tex_coord);
  if (!out.reason.empty()) return out;
  PrimitiveGeometry input;
  Status read;
  auto mesh = ReadTrianglePrimitive(*model_, p);
  if (mesh.ok()) {
    input.mesh = std::move(mesh).value();
    read = ReadTextures(*model_, p, tex_coord, &input);
  } else {
    read = mesh.status();
  }
  if (!read.ok()) {
    out.reason = read.ToString();
    out.failure = read;
    return out;
  }
  out.input_vertices = CountReferencedVertices(input.mesh);
  out.input_triangles = input.mesh.faces.size();
  const std::string label = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(primitive_index);
  auto geometry = compressor_(input, label);
  if (geometry.ok() && tex_coord >= 0 &&
      (geometry->texcoords.empty() || geometry->textures.size() != input.textures.size())) {
    geometry = InternalError("the compressor returned no texture atlas for material " + std::to_string(p.material) +
                             "'s textures");
  }
  Status status = geometry.ok() ? Replace(&p, *geometry) : geometry.status();
  if (!status.ok()) {
    out.reason = status.ToString();
    out.failure = status;
    return out;
  }
  out.compressed = true;
  out.output_vertices = geometry->decoded.positions.size();
  out.output_triangles = geometry->decoded.faces.size();
  out.stream_bytes = geometry->stream.size();
  out.levels = static_cast<int>(geometry->chunk_lengths.size()) - 1;
  out.psnr_db = geometry->psnr_db;
  return out;
}

}  // namespace

Status CompressPrimitives(tinygltf::Model* model, const GeometryCompressor& compressor,
                          const ContainerOptions& options, ConvertReport* report) {
  PrimitiveCompressor worker(model, compressor, options);
  ConvertReport local;
  ConvertReport* r = report != nullptr ? report : &local;
  for (size_t m = 0; m < model->meshes.size(); ++m) {
    for (size_t p = 0; p < model->meshes[m].primitives.size(); ++p) {
      PrimitiveOutcome outcome = worker.Compress(m, p);
      ++(outcome.compressed ? r->compressed : r->unchanged);
      r->primitives.push_back(std::move(outcome));
    }
  }
  if (r->compressed > 0) {
    AddExtensionName(&model->extensionsUsed, kExtensionName);
    if (!options.fallback) AddExtensionName(&model->extensionsRequired, kExtensionName);
  }
  if (worker.textures_replaced()) RemoveUnusedMaterials(model, worker.mutable_old_views());
  return RemoveUnusedData(model, worker.old_accessors(), worker.old_views());
}

}  // namespace eqmesh::gltf

#include "gltf/compress_primitives.h"

#include <numeric>
#include <set>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "gltf/extension.h"
#include "gltf/material_textures.h"
#include "gltf/primitive_appearance.h"

namespace eqmesh::gltf {
namespace {

// Empty when the primitive can be compressed, else why not.
std::string Disqualification(const tinygltf::Model& model, const tinygltf::Primitive& p,
                             const ContainerOptions& options, AppearancePlan* plan) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) return "mode " + std::to_string(p.mode) + " is not TRIANGLES";
  for (const auto& [name, value] : p.extensions) {
    if (name == kExtensionName || name == "KHR_draco_mesh_compression") return "already compressed with " + name;
  }
  if (!p.targets.empty()) return "has morph targets, which remeshing cannot carry";
  const std::string appearance = AppearanceDisqualification(model, p, plan);
  if (!appearance.empty()) return appearance;
  if (p.attributes.count("POSITION") == 0) return "has no POSITION";
  if (!options.drop_other_attributes) {
    for (const auto& [semantic, accessor] : p.attributes) {
      if (semantic != "POSITION" && semantic != "NORMAL" && !CarriedByAtlas(*plan, semantic)) {
        return "has attribute " + semantic + ", which remeshing cannot carry (drop_other_attributes drops it)";
      }
    }
  }
  return "";
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
  Status Replace(tinygltf::Primitive* p, const AppearancePlan& plan, const CompressedGeometry& geometry);
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

Status PrimitiveCompressor::Replace(tinygltf::Primitive* p, const AppearancePlan& plan,
                                    const CompressedGeometry& geometry) {
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
  ext.triangle_budget = geometry.triangle_budget;
  RememberOldData(*p);
  // NORMAL is always declared: without it glTF asks for flat shading, which shows
  // every facet of a remeshed scan.
  p->attributes = {{"POSITION", accessors.position}, {"NORMAL", accessors.normal}};
  if (textured) {
    p->attributes["TEXCOORD_0"] = accessors.texcoord;
    ReplaceAppearance(plan, geometry, model_, p);
    textures_replaced_ = true;
  }
  p->indices = accessors.indices;
  p->mode = TINYGLTF_MODE_TRIANGLES;
  p->extensions[kExtensionName] = ExtensionToValue(ext);
  return Status::Ok();
}

PrimitiveOutcome PrimitiveCompressor::Compress(size_t mesh_index, size_t primitive_index) {
  tinygltf::Primitive& p = model_->meshes[mesh_index].primitives[primitive_index];
  PrimitiveOutcome out;
  out.mesh = static_cast<int>(mesh_index);
  out.primitive = static_cast<int>(primitive_index);
  AppearancePlan plan;
  out.reason = Disqualification(*model_, p, options_, &plan);
  if (!out.reason.empty()) return out;
  PrimitiveGeometry input;
  Status read;
  auto mesh = ReadTrianglePrimitive(*model_, p);
  if (mesh.ok()) {
    input.mesh = std::move(mesh).value();
    read = ReadAppearance(*model_, p, plan, &input);
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
  if (geometry.ok() && plan.NeedsAtlas() &&
      (geometry->texcoords.empty() || geometry->textures.size() != input.textures.size())) {
    geometry = InternalError("the compressor returned no texture atlas for material " + std::to_string(p.material) +
                             "'s textures");
  }
  Status status = geometry.ok() ? Replace(&p, plan, *geometry) : geometry.status();
  if (!status.ok()) {
    out.reason = status.ToString();
    out.failure = status;
    return out;
  }
  out.compressed = true;
  // What a loader decodes by default: within the recorded budget.
  const Mesh& loaded = geometry->loaded.faces.empty() ? geometry->decoded : geometry->loaded;
  out.output_vertices = loaded.positions.size();
  out.output_triangles = loaded.faces.size();
  out.stream_bytes = geometry->stream.size();
  out.levels = static_cast<int>(geometry->chunk_lengths.size()) - 1;
  out.psnr_db = geometry->psnr_db;
  out.as_is = geometry->as_is;
  out.note = geometry->note;
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

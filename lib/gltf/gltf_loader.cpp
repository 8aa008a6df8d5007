#include "gltf/gltf_loader.h"

#include <set>

#include "gltf/accessor_io.h"
#include "gltf/buffer_layout.h"
#include "gltf/extension.h"
#include "gltf/gltf_io.h"
#include "mesh_io/file_bytes.h"

namespace eqmesh::gltf {
namespace {

std::string PrimitiveName(size_t mesh, size_t primitive) {
  return "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

// The stream bytes a level needs, proven to lie inside the buffer.
StatusOr<std::vector<uint8_t>> StreamPrefix(const tinygltf::Model& model, const NormalMeshExtension& ext,
                                            int level) {
  EQMESH_ASSIGN_OR_RETURN(const uint8_t* first, BufferViewData(model, ext.buffer_view, "the stream's bufferView"));
  const uint64_t size = ext.level_ranges[static_cast<size_t>(level)].end();
  return std::vector<uint8_t>(first, first + size);
}

// Rules 10 (the coder half) and 11: the stream header restates the JSON.
Status CheckStreamAgreesWithJson(const DecodedStream& decoded, const NormalMeshExtension& ext, int level) {
  if (decoded.stream_levels != ext.levels) {
    return CorruptStream("the stream has " + std::to_string(decoded.stream_levels) +
                         " levels, the extension says " + std::to_string(ext.levels) + " (rule 11)");
  }
  EQMESH_RETURN_IF_ERROR(CheckRangesForCoder(ext, decoded.coder));
  if (RangesFromLengths(decoded.chunk_lengths) != ext.level_ranges) {
    return CorruptStream("the stream's chunk sizes differ from levelByteRanges (rule 11)");
  }
  if (decoded.texcoords.empty() != (ext.texcoord_accessor < 0)) {
    return CorruptStream(ext.texcoord_accessor < 0 ? "the stream has an atlas but the extension declares no TEXCOORD_0 (rule 5)"
                                                   : "the extension declares TEXCOORD_0 but the stream has no atlas (rule 5)");
  }
  if (decoded.level_decoded != level) {
    return CorruptStream("decoded level " + std::to_string(decoded.level_decoded) + " instead of " +
                         std::to_string(level));
  }
  return Status::Ok();
}

Status CheckPlaceholderCounts(const tinygltf::Model& model, const tinygltf::Primitive& p,
                              const NormalMeshExtension& ext, const Mesh& mesh) {
  const size_t vertices = model.accessors[static_cast<size_t>(ext.position_accessor)].count;
  const size_t indices = model.accessors[static_cast<size_t>(p.indices)].count;
  if (vertices != mesh.positions.size() || indices != mesh.faces.size() * 3) {
    return CorruptStream("decoded " + std::to_string(mesh.positions.size()) + " vertices / " +
                         std::to_string(mesh.faces.size() * 3) + " indices, the accessors declare " +
                         std::to_string(vertices) + " / " + std::to_string(indices) + " (rule 11)");
  }
  return Status::Ok();
}

class PrimitiveDecoder {
 public:
  PrimitiveDecoder(tinygltf::Model* model, const LoadOptions& options)
      : model_(model),
        options_(options),
        decoder_(options.decoder ? options.decoder : EqmeshStreamDecoder()),
        fallback_(!IsExtensionRequired(*model)) {}

  Status Decode(size_t mesh_index, size_t primitive_index, PrimitiveLoad* load);
  const std::set<int>& stale_views() const { return stale_views_; }

 private:
  // An accessor another primitive has already filled is not overwritten: that
  // primitive keeps it and this one gets a copy.
  int ClaimAccessor(int index);
  void MarkStaleData(const tinygltf::Primitive& p, const NormalMeshExtension& ext);

  tinygltf::Model* model_;
  const LoadOptions& options_;
  StreamDecoderFn decoder_;
  bool fallback_;
  std::set<int> written_accessors_;
  std::set<int> stale_views_;
};

int PrimitiveDecoder::ClaimAccessor(int index) {
  if (index < 0) return index;
  if (written_accessors_.insert(index).second) return index;
  model_->accessors.push_back(model_->accessors[static_cast<size_t>(index)]);
  const int copy = static_cast<int>(model_->accessors.size()) - 1;
  written_accessors_.insert(copy);
  return copy;
}

void PrimitiveDecoder::MarkStaleData(const tinygltf::Primitive& p, const NormalMeshExtension& ext) {
  stale_views_.insert(ext.buffer_view);
  for (int a : {ext.position_accessor, ext.normal_accessor, ext.texcoord_accessor, p.indices}) {
    if (a >= 0 && model_->accessors[static_cast<size_t>(a)].bufferView >= 0) {
      stale_views_.insert(model_->accessors[static_cast<size_t>(a)].bufferView);
    }
  }
}

Status PrimitiveDecoder::Decode(size_t mesh_index, size_t primitive_index, PrimitiveLoad* load) {
  tinygltf::Primitive& p = model_->meshes[mesh_index].primitives[primitive_index];
  EQMESH_ASSIGN_OR_RETURN(const NormalMeshExtension ext, ParseExtension(p.extensions.at(kExtensionName)));
  EQMESH_RETURN_IF_ERROR(CheckExtensionAgainstModel(ext, p, *model_, fallback_));
  const int level = options_.max_level < 0 ? ext.levels : std::min(options_.max_level, ext.levels);
  EQMESH_ASSIGN_OR_RETURN(const std::vector<uint8_t> bytes, StreamPrefix(*model_, ext, level));
  const uint64_t budget =
      options_.max_triangles < 0 ? ext.triangle_budget : static_cast<uint64_t>(options_.max_triangles);
  EQMESH_ASSIGN_OR_RETURN(DecodedStream decoded,
                          decoder_(bytes.data(), bytes.size(), options_.max_level < 0 ? -1 : level, budget));
  EQMESH_RETURN_IF_ERROR(CheckStreamAgreesWithJson(decoded, ext, level));
  // The placeholders describe the whole finest level, which a budget may cut.
  const uint64_t full_triangles = model_->accessors[static_cast<size_t>(p.indices)].count / 3;
  if (level == ext.levels && (budget == 0 || budget >= full_triangles)) {
    EQMESH_RETURN_IF_ERROR(CheckPlaceholderCounts(*model_, p, ext, decoded.mesh));
  }

  MarkStaleData(p, ext);
  GeometryAccessors accessors{ClaimAccessor(ext.position_accessor), ClaimAccessor(ext.normal_accessor),
                              ClaimAccessor(p.indices), ClaimAccessor(ext.texcoord_accessor)};
  const GeometryData data{&decoded.mesh, decoded.normals.empty() ? nullptr : &decoded.normals,
                          decoded.texcoords.empty() ? nullptr : &decoded.texcoords};
  EQMESH_RETURN_IF_ERROR(WriteGeometry(model_, data, accessors, true).status());
  p.attributes["POSITION"] = accessors.position;
  if (accessors.normal >= 0) p.attributes["NORMAL"] = accessors.normal;
  if (accessors.texcoord >= 0) p.attributes["TEXCOORD_0"] = accessors.texcoord;
  p.indices = accessors.indices;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.extensions.erase(kExtensionName);
  *load = {static_cast<int>(mesh_index), static_cast<int>(primitive_index), ext.levels, level,
           bytes.size(), decoded.mesh.positions.size(), decoded.mesh.faces.size()};
  return Status::Ok();
}

}  // namespace

Status DecodeCompressedPrimitives(tinygltf::Model* model, const LoadOptions& options, LoadReport* report) {
  PrimitiveDecoder decoder(model, options);
  for (size_t m = 0; m < model->meshes.size(); ++m) {
    for (size_t p = 0; p < model->meshes[m].primitives.size(); ++p) {
      if (model->meshes[m].primitives[p].extensions.count(kExtensionName) == 0) continue;
      PrimitiveLoad load;
      EQMESH_RETURN_IF_ERROR(decoder.Decode(m, p, &load).WithContext(PrimitiveName(m, p)));
      if (report != nullptr) report->decoded.push_back(load);
    }
  }
  RemoveExtensionName(&model->extensionsUsed, kExtensionName);
  RemoveExtensionName(&model->extensionsRequired, kExtensionName);
  return RemoveUnusedData(model, {}, decoder.stale_views());
}

StatusOr<tinygltf::Model> LoadGltfFromBytes(const std::vector<uint8_t>& bytes, const std::string& name_for_errors,
                                            const LoadOptions& options, LoadReport* report) {
  EQMESH_ASSIGN_OR_RETURN(tinygltf::Model model, ReadGltfModelFromBytes(bytes, name_for_errors));
  EQMESH_RETURN_IF_ERROR(DecodeCompressedPrimitives(&model, options, report).WithContext(name_for_errors));
  return model;
}

StatusOr<tinygltf::Model> LoadGltf(const std::string& path, const LoadOptions& options, LoadReport* report) {
  EQMESH_ASSIGN_OR_RETURN(tinygltf::Model model, ReadGltfModel(path));
  EQMESH_RETURN_IF_ERROR(DecodeCompressedPrimitives(&model, options, report).WithContext(path));
  return model;
}

Status WriteDecodedGlb(const tinygltf::Model& model, const std::string& path) { return WriteGlb(model, path); }

}  // namespace eqmesh::gltf

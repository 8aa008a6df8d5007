// eqmesh info on a compressed glTF: see gltf_info.h.
#include "tools/gltf_info.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "coding/decoder.h"
#include "gltf/extension.h"
#include "gltf/gltf_io.h"
#include "gltf/gltf_loader.h"
#include "mesh_io/file_bytes.h"

namespace eqmesh::cli {
namespace {

bool HasGltfName(std::string path) {
  std::transform(path.begin(), path.end(), path.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0) path.resize(path.size() - 3);
  for (const char* ext : {".gltf", ".glb"}) {
    const size_t n = std::strlen(ext);
    if (path.size() >= n && path.compare(path.size() - n, n, ext) == 0) return true;
  }
  return false;
}

const char* CoderName(bitstream::CoderId c) {
  switch (c) {
    case bitstream::CoderId::kEq: return "eq";
    case bitstream::CoderId::kZerotree: return "zerotree";
    case bitstream::CoderId::kUniform: return "uniform";
  }
  return "unknown";
}

// What the extension object and the stream header say; the loader has checked
// both (and that they agree) before this runs.
StatusOr<GltfPrimitiveInfo> CompressedPrimitiveInfo(const tinygltf::Model& model, const tinygltf::Primitive& p) {
  GltfPrimitiveInfo info;
  info.compressed = true;
  EQMESH_ASSIGN_OR_RETURN(const gltf::NormalMeshExtension ext,
                          gltf::ParseExtension(p.extensions.at(gltf::kExtensionName)));
  info.levels = ext.levels;
  for (const gltf::ByteRange& range : ext.level_ranges) info.prefix_bytes.push_back(range.end());
  info.stream_bytes = ext.level_ranges.back().end();
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(ext.buffer_view)];
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  EQMESH_ASSIGN_OR_RETURN(const StreamInfo stream,
                          ReadStreamInfo(data.data() + view.byteOffset, ext.level_ranges.front().end()));
  info.coder = CoderName(stream.coder);
  return info;
}

uint64_t AccessorCount(const tinygltf::Model& model, int accessor) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= model.accessors.size()) return 0;
  return model.accessors[static_cast<size_t>(accessor)].count;
}

}  // namespace

bool IsCompressedGltf(const std::string& path) {
  if (!HasGltfName(path)) {
    const auto head = ReadFileBytes(path, 64u << 20);
    if (!head.ok() || head->size() < 4 || std::memcmp(head->data(), "glTF", 4) != 0) return false;
  }
  const StatusOr<tinygltf::Model> model = gltf::ReadGltfModel(path);
  if (!model.ok()) return false;
  const auto& used = model->extensionsUsed;
  return std::find(used.begin(), used.end(), gltf::kExtensionName) != used.end();
}

StatusOr<CompressedGltf> ReadCompressedGltf(const std::string& path) {
  EQMESH_ASSIGN_OR_RETURN(const tinygltf::Model model, gltf::ReadGltfModel(path));
  tinygltf::Model decoded = model;
  Status status = gltf::DecodeCompressedPrimitives(&decoded);
  if (!status.ok()) return status.WithContext(path);
  CompressedGltf out;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) {
      const tinygltf::Primitive& p = model.meshes[m].primitives[k];
      GltfPrimitiveInfo info;
      if (p.extensions.count(gltf::kExtensionName) != 0) {
        auto compressed = CompressedPrimitiveInfo(model, p);
        if (!compressed.ok()) return compressed.status().WithContext(path);
        info = std::move(compressed).value();
      }
      info.mesh = static_cast<int>(m);
      info.primitive = static_cast<int>(k);
      const tinygltf::Primitive& plain = decoded.meshes[m].primitives[k];
      const auto position = plain.attributes.find("POSITION");
      info.vertices = position == plain.attributes.end() ? 0 : AccessorCount(decoded, position->second);
      info.triangles = (plain.indices >= 0 ? AccessorCount(decoded, plain.indices) : info.vertices) / 3;
      out.primitives.push_back(std::move(info));
    }
  }
  auto flat = gltf::FlattenToMesh(decoded);
  if (!flat.ok()) return flat.status().WithContext(path);
  out.decoded = std::move(flat).value();
  return out;
}

StatusOr<Mesh> ReadMeshDecodingGltf(const std::string& path, ReadReport* report) {
  if (!IsCompressedGltf(path)) return ReadMesh(path, report);
  EQMESH_ASSIGN_OR_RETURN(CompressedGltf gltf, ReadCompressedGltf(path));
  if (report != nullptr) {
    *report = ReadReport();
    report->format = "gltf (EXT_normal_mesh_compression)";
  }
  return std::move(gltf.decoded);
}

}  // namespace eqmesh::cli

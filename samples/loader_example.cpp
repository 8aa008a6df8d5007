// How an engine uses the EXT_normal_mesh_compression loader.
//
//   loader_example FILE.glb [MAX_LEVEL]
//
// The loader returns a plain glTF 2.0 tinygltf::Model: after LoadGltf, an engine
// walks meshes -> primitives -> accessors -> bufferViews -> buffers exactly as it
// does for any glTF file and uploads the bytes (here: prints what it would upload).
// A progressive viewer first loads level 0 (the bytes of levelByteRanges[0] only)
// and shows it, then loads the full levels; this sample does both when no level is
// given.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gltf/gltf_loader.h"

namespace {

// What a renderer needs from an accessor to bind it as a vertex / index buffer.
struct GpuBufferDesc {
  const unsigned char* bytes = nullptr;
  size_t size = 0;
  size_t count = 0;
  int component_type = 0;
};

GpuBufferDesc Describe(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(accessor_index)];
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
  return {buffer.data.data() + view.byteOffset + a.byteOffset, view.byteLength - a.byteOffset, a.count,
          a.componentType};
}

void UploadScene(const tinygltf::Model& model, const eqmesh::gltf::LoadReport& report) {
  for (const auto& d : report.decoded) {
    std::printf("  decoded mesh %d primitive %d: level %d of %d, %llu stream bytes read\n", d.mesh, d.primitive,
                d.level_decoded, d.levels_in_stream, static_cast<unsigned long long>(d.stream_bytes_read));
  }
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      const auto pos = primitive.attributes.find("POSITION");
      if (pos == primitive.attributes.end() || primitive.indices < 0) continue;
      const GpuBufferDesc vertices = Describe(model, pos->second);
      const GpuBufferDesc indices = Describe(model, primitive.indices);
      const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(pos->second)];
      std::printf("  mesh %zu primitive %zu: %zu vertices (%zu B), %zu indices (%s, %zu B), material %d, "
                  "bounds [%g %g %g]-[%g %g %g]%s\n",
                  m, p, vertices.count, vertices.size, indices.count,
                  indices.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT ? "u32" : "u16", indices.size,
                  primitive.material, a.minValues[0], a.minValues[1], a.minValues[2], a.maxValues[0],
                  a.maxValues[1], a.maxValues[2], primitive.attributes.count("NORMAL") ? ", normals" : "");
    }
  }
}

int LoadAndUpload(const std::string& path, int max_level) {
  eqmesh::gltf::LoadOptions options;
  options.max_level = max_level;
  eqmesh::gltf::LoadReport report;
  auto model = eqmesh::gltf::LoadGltf(path, options, &report);
  if (!model.ok()) {
    // The error names the file and the primitive; an engine would show a
    // placeholder for that asset instead of silently dropping geometry.
    std::fprintf(stderr, "loader_example: %s\n", model.status().ToString().c_str());
    return 1;
  }
  std::printf("%s at max level %d:\n", path.c_str(), max_level);
  UploadScene(*model, report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: loader_example FILE.glb [MAX_LEVEL]\n");
    return 2;
  }
  if (argc == 3) return LoadAndUpload(argv[1], std::atoi(argv[2]));
  // Progressive: coarse first, then everything.
  const int coarse = LoadAndUpload(argv[1], 0);
  return coarse != 0 ? coarse : LoadAndUpload(argv[1], -1);
}

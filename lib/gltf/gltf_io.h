// Reading and writing whole glTF models with tinygltf, for the converter and the
// loader. Images are never decoded: their encoded bytes (PNG, JPEG, KTX2, ...) are
// carried through unchanged, so converting or loading a file cannot alter a texture.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"

namespace eqmesh::gltf {

// Reads a .gltf or .glb (by content, not by name; gzip is inflated). External
// buffers and images of a .gltf are resolved beside it. Errors name the file.
StatusOr<tinygltf::Model> ReadGltfModel(const std::string& path);

// Same on bytes in memory. `base_dir` resolves external URIs of a .gltf (empty: none
// allowed). `name_for_errors` prefixes every message.
StatusOr<tinygltf::Model> ReadGltfModelFromBytes(const std::vector<uint8_t>& bytes,
                                                 const std::string& name_for_errors,
                                                 const std::string& base_dir = "");

// A self-contained GLB: every buffer merged into the BIN chunk and every image with
// loaded bytes embedded as a bufferView. The input model is not changed.
// image/png or image/jpeg by the leading bytes (application/octet-stream else).
std::string GuessMimeType(const std::vector<unsigned char>& bytes);

StatusOr<std::vector<uint8_t>> WriteGlbToBytes(const tinygltf::Model& model);
Status WriteGlb(const tinygltf::Model& model, const std::string& path);

}  // namespace eqmesh::gltf

// Converter to EXT_normal_mesh_compression: glTF / GLB / OBJ / PLY / OFF in,
// compressed GLB out. Each TRIANGLES primitive that qualifies is remeshed (in its
// mesh's local space) and encoded; every other primitive, and everything that is
// not primitive geometry (nodes, materials, textures, animations, cameras, skins,
// extras, other extensions), is written unchanged. A mesh file (OBJ/PLY/OFF) becomes
// a one-mesh, one-node scene.
#pragma once

#include <cstdint>
#include <string>

#include <tiny_gltf.h>

#include "coding/encoder.h"
#include "core/status.h"
#include "gltf/compress_primitives.h"
#include "remesh/remesh.h"

namespace eqmesh::gltf {

struct ConvertOptions {
  // Codec settings. input_vertices and original are filled per primitive.
  EncodeOptions codec;
  RemeshOptions remesh;
  // See ContainerOptions.
  bool fallback = false;
  bool drop_other_attributes = false;
  // A triangle primitive that cannot be compressed (broken geometry) is left
  // unchanged with its reason in the report, unless `strict`; the conversion
  // fails, writing nothing, when `strict` or when no primitive at all could be
  // compressed (the output would only be a re-packed copy of the input).
  bool strict = false;
  // A primitive whose decoded stream measures below this PSNR against the
  // primitive (dB, the `eqmesh compare` meter) is left unchanged, as one that
  // cannot be compressed: a broken remesh is never shipped. 0: no floor.
  double min_psnr = 60.0;
  // Side of a textured primitive's atlas images in texels; 0: each input
  // texture's own size.
  uint32_t texture_size = 0;
  // Triangle budget each primitive is decoded within, recorded as the extension's
  // triangleBudget (loaders' default) and measured by PSNR targets: -1: the
  // primitive's own triangle count (a decoded asset is never heavier than its
  // source); 0: none; N: N. Textured primitives get none (their atlas seams are
  // split per uniform level).
  int64_t max_triangles = -1;
};

// The remesher + encoder as a GeometryCompressor (also measures the decoded PSNR
// when options.codec.measure_psnr or target_psnr asks for it).
GeometryCompressor MakeEqmeshCompressor(const ConvertOptions& options);

// Compresses `model` in place (no file written).
StatusOr<ConvertReport> ConvertModel(tinygltf::Model* model, const ConvertOptions& options);

// Reads `input_path` (.gltf/.glb by content or name, else any mesh format ReadMesh
// accepts) and writes the compressed GLB to `output_path`.
StatusOr<ConvertReport> ConvertToCompressedGltf(const std::string& input_path, const std::string& output_path,
                                                const ConvertOptions& options);

// Same from a model in memory.
StatusOr<ConvertReport> ConvertToCompressedGltf(tinygltf::Model model, const std::string& output_path,
                                                const ConvertOptions& options);

}  // namespace eqmesh::gltf

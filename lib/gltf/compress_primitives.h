// The container half of the converter: replaces the geometry of a model's triangle
// primitives by EXT_normal_mesh_compression streams. The compression itself is a
// function argument (GeometryCompressor), so this file knows glTF, not the codec:
// gltf_converter.h plugs in the remesher and encoder, tests plug in stand-ins.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh::gltf {

// A texture the primitive's material samples, to be painted into the primitive's
// new atlas, or (no image) the primitive's COLOR_0 alone as a new base colour.
struct TextureJob {
  std::vector<uint8_t> encoded;  // the image file (PNG or JPEG); empty: white
  bool times_vertex_colors = false;  // multiplied by the primitive's COLOR_0
  bool normal_map = false;           // tangent-space normals: re-expressed, not copied
  double normal_scale = 1.0;         // normalTexture.scale, baked into the new map
  int wrap_s = 10497, wrap_t = 10497;
  // KHR_texture_transform as u' = m[0] u + m[1] v + m[2], v' = m[3] u + m[4] v + m[5].
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};
};

// One primitive as the compressor sees it.
struct PrimitiveGeometry {
  Mesh mesh;  // local space, vertices as stored
  // The TEXCOORD_n its material samples, per vertex; empty when it samples none.
  std::vector<std::array<double, 2>> texcoords;
  std::vector<std::array<double, 3>> colors;  // COLOR_0 (RGB) per vertex, when baked
  // NORMAL and TANGENT as stored, when a normal map needs the input's frames
  // (empty: not given, computed).
  std::vector<Vec3> normals;
  std::vector<std::array<double, 4>> tangents;
  std::vector<TextureJob> textures;          // empty: no atlas
};

struct CompressedGeometry {
  std::vector<uint8_t> stream;
  std::vector<uint64_t> chunk_lengths;  // levels + 1: header+base+kept+atlas, then each level
  Mesh decoded;                         // full-resolution decoded mesh (placeholders, fallback)
  std::vector<Vec3> normals;            // per decoded vertex; empty: the spec rule on `decoded`
  std::vector<std::array<float, 2>> texcoords;  // TEXCOORD_0 when the primitive has an atlas
  std::vector<std::vector<uint8_t>> textures;   // per TextureJob: the atlas image, same format
  double psnr_db = 0;                   // decoded vs. input, when measured (else 0)
  uint64_t triangle_budget = 0;         // the extension's triangleBudget (0: none)
  Mesh loaded;                          // what a loader decodes within it (empty: `decoded`)
  std::string note;                     // a warning for the report (empty: none)
  bool as_is = false;                   // the stream codes the input as is, not a normal mesh
};

// Compresses one primitive; `label` ("mesh 0 primitive 1") is for progress and
// errors. An error leaves that primitive unchanged.
using GeometryCompressor =
    std::function<StatusOr<CompressedGeometry>(const PrimitiveGeometry& primitive, const std::string& label)>;

struct ContainerOptions {
  // Write the decoded geometry as real accessors and list the extension in
  // extensionsUsed only, so loaders without it still open the file (spec rule 12).
  bool fallback = false;
  // Compress primitives with attributes other than POSITION, NORMAL and the
  // TEXCOORD_n their material samples (COLOR_0, TANGENT, ...) by dropping those
  // attributes; false leaves such primitives as they are (remeshing cannot carry
  // per-vertex data).
  bool drop_other_attributes = false;
};

struct PrimitiveOutcome {
  int mesh = 0;
  int primitive = 0;
  bool compressed = false;
  std::string reason;  // why it was left unchanged (empty when compressed)
  // Set when the primitive was a candidate (triangles, positions) whose
  // geometry could not be read or compressed, as opposed to one that is not
  // ours to compress (points, lines, another compression extension).
  Status failure;
  size_t input_vertices = 0, input_triangles = 0;
  size_t output_vertices = 0, output_triangles = 0;
  size_t stream_bytes = 0;
  int levels = 0;
  bool as_is = false;  // coded as is (representation_choice.h), not as a normal mesh
  double psnr_db = 0;
  std::string note;  // a warning about a compressed primitive (empty: none)
};

struct ConvertReport {
  std::vector<PrimitiveOutcome> primitives;  // every primitive, in mesh order
  size_t compressed = 0;
  size_t unchanged = 0;
  uint64_t input_bytes = 0;   // input file size (0 for an in-memory model)
  uint64_t output_bytes = 0;  // GLB written
  std::vector<std::string> notes;
};

// Compresses every primitive that qualifies, leaves the others (listed in the
// report with the reason), drops the data only the replaced primitives used, and
// updates extensionsUsed / extensionsRequired. Fails only when the model itself is
// broken; per-primitive failures are outcomes, not errors.
Status CompressPrimitives(tinygltf::Model* model, const GeometryCompressor& compressor,
                          const ContainerOptions& options, ConvertReport* report);

}  // namespace eqmesh::gltf

// Texture transfer: paints a remeshed primitive's atlas (atlas_builder.h) from the
// input's own textures. For each texel of the atlas, the point of the decoded
// surface it maps to, the closest point of the input surface, the input's
// TEXCOORD there (the input's own UV seams do not matter: the lookup is by face)
// and the input texture sampled bilinearly with its sampler's wrap modes and
// KHR_texture_transform. Texels outside every triangle are filled by dilation, so
// bilinear filtering and mip-mapping near chart borders read the chart's colours.
//
// Follows the attribute-transfer step of texture baking (e.g. Sander et al.,
// "Signal-specialized parametrization", EGWR 2002, §6; MPEG V-DMC's texture
// transfer): closest-point correspondence, not a ray along the normal, since the
// decoded surface lies within the codec's error of the input.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "coding/atlas/atlas_layout.h"
#include "core/status.h"
#include "mesh/semi_regular.h"
#include "texture/image_codec.h"
#include "texture/tangent_frames.h"

namespace eqmesh::texture {

// Where each texel of an atlas image lands on the input: input face and
// barycentric coordinates (face kNoTexelFace: a gutter texel).
inline constexpr uint32_t kNoTexelFace = 0xFFFFFFFFu;
struct TexelSource {
  uint32_t face = kNoTexelFace;
  std::array<float, 3> barycentric{};
  // Where the texel lies on the decoded surface: a face of its finest level
  // (ExtractLevel's numbering, kept faces last) and barycentric coordinates.
  uint32_t decoded_face = 0;
  std::array<float, 3> decoded_barycentric{};
};
struct TexelMap {
  uint32_t width = 0, height = 0;
  int dilation_passes = 0;  // enough to fill the gutters between cells
  std::vector<TexelSource> texels;  // row-major, top row first
};

// The input primitive as stored (vertices split at its UV seams) with the
// texture coordinates the material samples, one per vertex.
struct TexturedInput {
  const Mesh* mesh = nullptr;
  const std::vector<std::array<double, 2>>* texcoords = nullptr;
};

// What re-expresses a tangent-space normal map: the input's frames (per input
// vertex) and the decoded surface's (per vertex of its finest level as the loader
// writes it: split at the atlas seams, faces in ExtractLevel's order).
struct NormalMapFrames {
  const std::vector<Vec4>* input_tangents = nullptr;
  const std::vector<Vec3>* input_normals = nullptr;
  const Mesh* decoded = nullptr;
  const std::vector<Vec4>* decoded_tangents = nullptr;
  const std::vector<Vec3>* decoded_normals = nullptr;
  double scale = 1.0;  // the slot's normalTexture.scale, baked into the new map
};

// One input texture and how the material samples it.
struct SourceTexture {
  const Image* image = nullptr;  // null: white (a base colour made of vertex colours alone)
  int wrap_s = 10497, wrap_t = 10497;  // glTF sampler wrap modes (REPEAT)
  // KHR_texture_transform as an affine map: u' = m[0] u + m[1] v + m[2],
  // v' = m[3] u + m[4] v + m[5].
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};
  // Per input vertex RGB in [0, 1] that multiplies the texture (COLOR_0 baked
  // into the base colour); null: none.
  const std::vector<std::array<double, 3>>* vertex_colors = nullptr;
  // A tangent-space normal map: each texel's vector goes from the input's frame
  // to the decoded surface's; null: colours, painted as they are.
  const NormalMapFrames* normal_map = nullptr;
};

// Bilinear sample of the texture at (u, v) after the sampler's wrap modes (the
// transform is the caller's), as a GPU's LINEAR filter samples texel centres:
// out receives image->channels values in [0, 255].
void SampleBilinear(const SourceTexture& source, double u, double v, float* out);

// Catmull-Rom bicubic sample (same conventions, clamped to [0, 255]): sharper than
// bilinear, so an atlas painted with it loses less of the input's detail to the
// second resampling a renderer's bilinear filter adds.
void SampleBicubic(const SourceTexture& source, double u, double v, float* out);

// Texel correspondences of `decoded` (full resolution) laid out by `atlas`, for an
// image of width x height (the atlas grid scaled to it).
StatusOr<TexelMap> MapAtlasTexels(const SemiRegularMesh& decoded, const AtlasLayout& atlas,
                                  const TexturedInput& input, uint32_t width, uint32_t height);

// The atlas image of `source`, gutters dilated: the image's channel count, gray
// widened to RGB when vertex colours multiply it, RGB without an image.
Image PaintAtlas(const TexelMap& map, const TexturedInput& input, const SourceTexture& source);

}  // namespace eqmesh::texture

#include "gltf/textured_compression.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "coding/atlas/attach_atlas.h"
#include "coding/decoded_geometry.h"
#include "coding/decoder.h"
#include "gltf/stream_decoder.h"
#include "texture/atlas_builder.h"
#include "texture/image_codec.h"
#include "texture/tangent_frames.h"
#include "texture/texture_transfer.h"

namespace eqmesh::gltf {
namespace {

// JPEG quality when the input's tables match no IJG quality.
constexpr int kFallbackJpegQuality = 90;

struct DecodedTexture {
  bool has_image = false;  // false: COLOR_0 alone, painted as JPEG
  texture::Image image;
  texture::ImageFormat format = texture::ImageFormat::kJpeg;
  int jpeg_quality = kFallbackJpegQuality;
};

StatusOr<DecodedTexture> DecodeJobImage(const TextureJob& job) {
  DecodedTexture out;
  if (job.encoded.empty()) return out;
  out.has_image = true;
  EQMESH_ASSIGN_OR_RETURN(out.format, texture::SniffImageFormat(job.encoded.data(), job.encoded.size()));
  EQMESH_ASSIGN_OR_RETURN(out.image, texture::DecodeImage(job.encoded.data(), job.encoded.size()));
  if (out.format == texture::ImageFormat::kJpeg) {
    const int q = texture::EstimateJpegQuality(job.encoded.data(), job.encoded.size());
    if (q > 0) out.jpeg_quality = q;
  }
  return out;
}

// Gutters of 1/256 of the texture side (at least 2 texels) on each side of a cell
// border: 8 texels between charts at 1024, which keeps charts apart down to the
// 1/4-size mip level.
uint32_t GutterFor(uint32_t width, uint32_t height) { return std::max<uint32_t>(2, std::min(width, height) / 256); }

StatusOr<std::vector<uint8_t>> Encode(const texture::Image& image, const DecodedTexture& like) {
  if (like.format == texture::ImageFormat::kJpeg) return texture::EncodeJpeg(image, like.jpeg_quality);
  return texture::EncodePng(image);
}

// The frames the input's normal map was authored against: TANGENT and NORMAL as
// given, else derived (normals on the welded surface, so UV seams do not crease
// them).
struct InputFrames {
  std::vector<Vec3> normals;
  std::vector<texture::Vec4> tangents;
};

InputFrames FramesOfInput(const PrimitiveGeometry& input) {
  InputFrames f;
  f.normals = input.normals;
  if (f.normals.empty()) {
    std::vector<uint32_t> welded_index;
    const std::vector<Vec3> welded = UnitVertexNormals(WeldedByPosition(input.mesh, &welded_index));
    for (uint32_t w : welded_index) f.normals.push_back(welded[w]);
  }
  if (input.tangents.empty()) {
    f.tangents = texture::VertexTangents(input.mesh, input.texcoords, f.normals);
  } else {
    for (const auto& t : input.tangents) f.tangents.emplace_back(t[0], t[1], t[2], t[3] < 0 ? -1.0 : 1.0);
  }
  return f;
}

struct DecodedFrames {
  std::vector<Vec3> normals;
  std::vector<texture::Vec4> tangents;
};

DecodedFrames FramesOfDecoded(const CompressedGeometry& out) {
  DecodedFrames f;
  f.normals = out.normals.empty() ? UnitVertexNormals(out.decoded) : out.normals;
  std::vector<std::array<double, 2>> uv;
  for (const auto& t : out.texcoords) uv.push_back({t[0], t[1]});
  f.tangents = texture::VertexTangents(out.decoded, uv, f.normals);
  return f;
}

// What a loader decodes from the stream with its atlas: the atlas changes no level
// chunk, so the stream decoded before it was attached, split at the atlas's seams.
Status UseTexturedDecode(const SemiRegularMesh& decoded, const AtlasLayout& atlas, CompressedGeometry* out) {
  EQMESH_ASSIGN_OR_RETURN(out->chunk_lengths, EqmeshStreamLayout()(out->stream.data(), out->stream.size()));
  DecodedGeometry geometry = ExtractDecodedGeometry(decoded, &atlas);
  out->decoded = std::move(geometry.mesh);
  out->normals = std::move(geometry.normals);
  out->texcoords = std::move(geometry.texcoords);
  return Status::Ok();
}

}  // namespace

Mesh WeldedByPosition(const Mesh& mesh, std::vector<uint32_t>* welded_index) {
  std::map<std::array<uint64_t, 3>, uint32_t> first;
  std::vector<uint32_t> local;
  std::vector<uint32_t>& remap = welded_index != nullptr ? *welded_index : local;
  remap.assign(mesh.positions.size(), 0);
  Mesh out;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    std::array<uint64_t, 3> key{};
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.positions[v][c] == 0.0 ? 0.0 : mesh.positions[v][c];  // -0 == +0
      std::memcpy(&key[static_cast<size_t>(c)], &x, sizeof x);
    }
    const auto [it, added] = first.emplace(key, static_cast<uint32_t>(out.positions.size()));
    if (added) out.positions.push_back(mesh.positions[v]);
    remap[v] = it->second;
  }
  out.faces.reserve(mesh.faces.size());
  for (const Face& f : mesh.faces) out.faces.push_back({remap[f[0]], remap[f[1]], remap[f[2]]});
  return out;
}

// Side of an atlas painted from vertex colours alone: about four texels per input
// vertex once the cells' gutters and packing are paid (vertex colours vary
// linearly across a face, so a few texels per face carry them).
uint32_t VertexColorSide(size_t vertices) {
  uint32_t side = 256;
  while (side < 4096 && static_cast<double>(side) * side < 8.0 * static_cast<double>(vertices)) side *= 2;
  return side;
}

Status AddAtlasAndTextures(const PrimitiveGeometry& input, uint32_t texture_size, CompressedGeometry* out) {
  std::vector<DecodedTexture> sources;
  const uint32_t colour_side = texture_size > 0 ? texture_size : VertexColorSide(input.mesh.positions.size());
  uint32_t grid_w = texture_size, grid_h = texture_size;
  for (const TextureJob& job : input.textures) {
    EQMESH_ASSIGN_OR_RETURN(DecodedTexture t, DecodeJobImage(job));
    if (texture_size == 0) {
      grid_w = std::max(grid_w, t.has_image ? static_cast<uint32_t>(t.image.width) : colour_side);
      grid_h = std::max(grid_h, t.has_image ? static_cast<uint32_t>(t.image.height) : colour_side);
    }
    sources.push_back(std::move(t));
  }
  if (grid_w == 0 || grid_h == 0) return InvalidArgument("a primitive without textures or COLOR_0 needs no atlas");
  EQMESH_ASSIGN_OR_RETURN(const SemiRegularMesh decoded, DecodeSemiRegular(out->stream.data(), out->stream.size()));
  EQMESH_ASSIGN_OR_RETURN(const AtlasLayout atlas,
                          texture::BuildAtlas(decoded, {grid_w, grid_h, GutterFor(grid_w, grid_h)}));
  EQMESH_ASSIGN_OR_RETURN(out->stream, AttachAtlas(out->stream, atlas));
  EQMESH_RETURN_IF_ERROR(UseTexturedDecode(decoded, atlas, out));
  const texture::TexturedInput textured{&input.mesh, &input.texcoords};
  std::map<std::pair<uint32_t, uint32_t>, texture::TexelMap> maps;
  const bool any_normal_map = std::any_of(input.textures.begin(), input.textures.end(),
                                          [](const TextureJob& j) { return j.normal_map; });
  const InputFrames from = any_normal_map ? FramesOfInput(input) : InputFrames();
  const DecodedFrames to = any_normal_map ? FramesOfDecoded(*out) : DecodedFrames();
  for (size_t k = 0; k < sources.size(); ++k) {
    const bool own_size = texture_size == 0 && sources[k].has_image;
    const uint32_t w = own_size ? static_cast<uint32_t>(sources[k].image.width) : (texture_size > 0 ? texture_size : colour_side);
    const uint32_t h = own_size ? static_cast<uint32_t>(sources[k].image.height) : (texture_size > 0 ? texture_size : colour_side);
    const std::pair<uint32_t, uint32_t> size{w, h};
    if (maps.count(size) == 0) {
      EQMESH_ASSIGN_OR_RETURN(maps[size], texture::MapAtlasTexels(decoded, atlas, textured, w, h));
    }
    const TextureJob& job = input.textures[k];
    const texture::NormalMapFrames frames{&from.tangents, &from.normals, &out->decoded,
                                          &to.tangents,   &to.normals,   job.normal_scale};
    const texture::SourceTexture source{sources[k].has_image ? &sources[k].image : nullptr, job.wrap_s, job.wrap_t,
                                        job.uv_transform, job.times_vertex_colors ? &input.colors : nullptr,
                                        job.normal_map ? &frames : nullptr};
    const texture::Image painted = texture::PaintAtlas(maps.at(size), textured, source);
    EQMESH_ASSIGN_OR_RETURN(std::vector<uint8_t> bytes, Encode(painted, sources[k]));
    out->textures.push_back(std::move(bytes));
  }
  return Status::Ok();
}

}  // namespace eqmesh::gltf

#include "texture/texture_transfer.h"

#include <algorithm>
#include <cmath>

#include "coding/atlas/seam_split.h"
#include "coding/decoder.h"
#include "mesh/triangle_bvh.h"
#include "core/parallel_for.h"

namespace eqmesh::texture {
namespace {

constexpr int kRepeat = 10497, kMirroredRepeat = 33648;

// The level faces an atlas face covers: a base face's block of finest faces, or
// the kept face itself.
std::pair<size_t, size_t> LevelFaceRange(const SemiRegularMesh& mesh, uint32_t atlas_face) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  const size_t base = h.BaseFaces().size();
  const size_t per_base = h.Faces(h.levels()).size() / std::max<size_t>(1, base);
  if (atlas_face < base) return {atlas_face * per_base, (atlas_face + 1) * per_base};
  const size_t kept = h.Faces(h.levels()).size() + (atlas_face - base);
  return {kept, kept + 1};
}

struct Rasterizer {
  const Mesh& welded;
  const std::vector<FaceTexCoords>& uvs;
  const TriangleBvh& bvh;
  TexelMap* map;

  // Texel centres inside the face's texture triangle (the first face to claim a
  // texel keeps it); each gets the input point closest to its surface point.
  void RasterizeFace(size_t f) const {
    std::array<std::array<double, 2>, 3> p;
    for (size_t k = 0; k < 3; ++k) p[k] = {uvs[f][k][0] * map->width, uvs[f][k][1] * map->height};
    const double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (area == 0.0) return;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0][0], p[1][0], p[2][0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0][1], p[1][1], p[2][1]}))));
    const int x1 = std::min<int>(static_cast<int>(map->width) - 1, static_cast<int>(std::max({p[0][0], p[1][0], p[2][0]})));
    const int y1 = std::min<int>(static_cast<int>(map->height) - 1, static_cast<int>(std::max({p[0][1], p[1][1], p[2][1]})));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) Texel(f, p, area, x, y);
    }
  }

  void Texel(size_t f, const std::array<std::array<double, 2>, 3>& p, double area, int x, int y) const {
    TexelSource& out = map->texels[static_cast<size_t>(y) * map->width + static_cast<size_t>(x)];
    if (out.face != kNoTexelFace) return;
    const double cx = x + 0.5, cy = y + 0.5;
    std::array<double, 3> b;
    for (size_t k = 0; k < 3; ++k) {
      const auto& a = p[(k + 1) % 3];
      const auto& c = p[(k + 2) % 3];
      b[k] = ((c[0] - a[0]) * (cy - a[1]) - (cx - a[0]) * (c[1] - a[1])) / area;
    }
    if (b[0] < 0 || b[1] < 0 || b[2] < 0) return;
    const eqmesh::Face& face = welded.faces[f];
    const Vec3 point = b[0] * welded.positions[face[0]] + b[1] * welded.positions[face[1]] +
                       b[2] * welded.positions[face[2]];
    const ClosestPointResult hit = bvh.ClosestPoint(point);
    if (!hit.found()) return;
    out.face = hit.face;
    out.barycentric = {static_cast<float>(hit.barycentric[0]), static_cast<float>(hit.barycentric[1]),
                       static_cast<float>(hit.barycentric[2])};
    out.decoded_face = static_cast<uint32_t>(f);
    out.decoded_barycentric = {static_cast<float>(b[0]), static_cast<float>(b[1]), static_cast<float>(b[2])};
  }
};

double Wrap(double t, int mode) {
  if (mode == kRepeat) return t - std::floor(t);
  if (mode == kMirroredRepeat) {
    const double m = t - 2.0 * std::floor(t * 0.5);
    return m <= 1.0 ? m : 2.0 - m;
  }
  return std::clamp(t, 0.0, 1.0);
}

int WrapIndex(int i, int n, int mode) {
  if (mode == kRepeat) return ((i % n) + n) % n;
  if (mode == kMirroredRepeat) {
    const int period = 2 * n;
    const int m = ((i % period) + period) % period;
    return m < n ? m : period - 1 - m;
  }
  return std::clamp(i, 0, n - 1);
}

}  // namespace

void SampleBilinear(const SourceTexture& s, double u, double v, float* out) {
  const Image& im = *s.image;
  const double x = Wrap(u, s.wrap_s) * im.width - 0.5, y = Wrap(v, s.wrap_t) * im.height - 0.5;
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  const double fx = x - xi, fy = y - yi;
  const int c = im.channels;
  for (int ch = 0; ch < c; ++ch) out[ch] = 0.0f;
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const size_t row = static_cast<size_t>(WrapIndex(yi + dy, im.height, s.wrap_t));
      const size_t col = static_cast<size_t>(WrapIndex(xi + dx, im.width, s.wrap_s));
      const uint8_t* px = &im.pixels[(row * static_cast<size_t>(im.width) + col) * static_cast<size_t>(c)];
      for (int ch = 0; ch < c; ++ch) out[ch] += static_cast<float>(w * px[ch]);
    }
  }
}

namespace {

// Catmull-Rom weights of the four texels around fraction t (Keys 1981, a = -0.5).
std::array<double, 4> CubicWeights(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2};
}

}  // namespace

void SampleBicubic(const SourceTexture& s, double u, double v, float* out) {
  const Image& im = *s.image;
  const double x = Wrap(u, s.wrap_s) * im.width - 0.5, y = Wrap(v, s.wrap_t) * im.height - 0.5;
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  const std::array<double, 4> wx = CubicWeights(x - xi), wy = CubicWeights(y - yi);
  const int c = im.channels;
  double sum[4] = {0, 0, 0, 0};
  for (int dy = 0; dy < 4; ++dy) {
    const size_t row = static_cast<size_t>(WrapIndex(yi + dy - 1, im.height, s.wrap_t));
    for (int dx = 0; dx < 4; ++dx) {
      const size_t col = static_cast<size_t>(WrapIndex(xi + dx - 1, im.width, s.wrap_s));
      const double w = wx[static_cast<size_t>(dx)] * wy[static_cast<size_t>(dy)];
      const uint8_t* px = &im.pixels[(row * static_cast<size_t>(im.width) + col) * static_cast<size_t>(c)];
      for (int ch = 0; ch < c; ++ch) sum[ch] += w * px[ch];
    }
  }
  for (int ch = 0; ch < c; ++ch) out[ch] = static_cast<float>(std::clamp(sum[ch], 0.0, 255.0));
}

namespace {

// Each pass gives every empty texel with a filled 8-neighbour their mean: enough
// passes to cross the gutters between cells.
void Dilate(uint32_t width, uint32_t height, int channels, int passes, std::vector<float>* color,
            std::vector<bool>* filled) {
  const int w = static_cast<int>(width), h = static_cast<int>(height);
  std::vector<size_t> frontier;
  std::vector<float> mean(static_cast<size_t>(channels));
  for (int pass = 0; pass < passes; ++pass) {
    frontier.clear();
    std::vector<float> next = *color;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y) * width + static_cast<size_t>(x);
        if ((*filled)[i]) continue;
        int n = 0;
        std::fill(mean.begin(), mean.end(), 0.0f);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const size_t j = static_cast<size_t>(ny) * width + static_cast<size_t>(nx);
            if (!(*filled)[j]) continue;
            for (int c = 0; c < channels; ++c) mean[static_cast<size_t>(c)] += (*color)[j * static_cast<size_t>(channels) + static_cast<size_t>(c)];
            ++n;
          }
        }
        if (n == 0) continue;
        for (int c = 0; c < channels; ++c) next[i * channels + c] = mean[static_cast<size_t>(c)] / static_cast<float>(n);
        frontier.push_back(i);
      }
    }
    for (size_t i : frontier) (*filled)[i] = true;
    color->swap(next);
    if (frontier.empty()) break;
  }
}

// Texels no cell reaches (the atlas's unused area) take the mean colour: flat
// areas cost a JPEG or PNG almost nothing.
void FillRemaining(int channels, std::vector<float>* color, const std::vector<bool>& filled) {
  std::vector<double> sum(static_cast<size_t>(channels), 0.0);
  size_t n = 0;
  for (size_t i = 0; i < filled.size(); ++i) {
    if (!filled[i]) continue;
    for (int c = 0; c < channels; ++c) sum[static_cast<size_t>(c)] += (*color)[i * channels + c];
    ++n;
  }
  for (size_t i = 0; i < filled.size(); ++i) {
    if (filled[i]) continue;
    for (int c = 0; c < channels; ++c) {
      (*color)[i * channels + c] = n > 0 ? static_cast<float>(sum[static_cast<size_t>(c)] / static_cast<double>(n)) : 0.0f;
    }
  }
}

}  // namespace

StatusOr<TexelMap> MapAtlasTexels(const SemiRegularMesh& decoded, const AtlasLayout& atlas,
                                  const TexturedInput& input, uint32_t width, uint32_t height) {
  EQMESH_ASSIGN_OR_RETURN(const TriangleBvh bvh, TriangleBvh::Build(*input.mesh));
  const int level = decoded.hierarchy.levels();
  const Mesh welded = ExtractLevel(decoded, level);
  const std::vector<FaceTexCoords> uvs =
      LevelCornerTexCoords(decoded, level, FaceCornerTexCoords(atlas, AtlasFaces(decoded)));
  TexelMap map;
  map.width = width;
  map.height = height;
  map.texels.assign(static_cast<size_t>(width) * height, TexelSource{});
  const double scale = std::max(static_cast<double>(width) / atlas.width, static_cast<double>(height) / atlas.height);
  map.dilation_passes = static_cast<int>(std::ceil(2.0 * atlas.gutter * scale)) + 2;
  const Rasterizer raster{welded, uvs, bvh, &map};
  // Cells never overlap, so threads that take whole cells write disjoint texels
  // and the first-claim rule inside a cell stays deterministic.
  ParallelFor(atlas.cells.size(), [&](size_t begin, size_t end, size_t) {
    for (size_t c = begin; c < end; ++c) {
      const AtlasCell& cell = atlas.cells[c];
      for (uint32_t face : {cell.face_a, cell.face_b}) {
        if (face == cell.face_b && !cell.paired) break;
        const auto [first, last] = LevelFaceRange(decoded, face);
        for (size_t f = first; f < last; ++f) raster.RasterizeFace(f);
      }
    }
  }, 4);
  return map;
}

namespace {

// Channels of the painted atlas: vertex colours make a gray image colour.
int PaintedChannels(const SourceTexture& s) {
  if (s.image == nullptr) return 3;
  if (s.vertex_colors == nullptr || s.image->channels >= 3) return s.image->channels;
  return s.image->channels + 2;  // gray -> RGB, gray + alpha -> RGBA
}

// The sampled vector (texel values 0..255 -> -1..1, xy times the scale) moved from
// the input's tangent frame to the decoded surface's, back to texel values.
void ReexpressNormal(const TexelSource& t, const TexturedInput& input, const NormalMapFrames& f, float* rgb) {
  Vec3 v(rgb[0] / 127.5 - 1.0, rgb[1] / 127.5 - 1.0, rgb[2] / 127.5 - 1.0);
  v.x() *= f.scale;
  v.y() *= f.scale;
  const Frame from = FrameAt(*input.mesh, *f.input_tangents, *f.input_normals, t.face, t.barycentric);
  const Frame to = FrameAt(*f.decoded, *f.decoded_tangents, *f.decoded_normals, t.decoded_face, t.decoded_barycentric);
  Vec3 object = v.x() * from.t + v.y() * from.b + v.z() * from.n;
  object = object.squaredNorm() > 0 ? object.normalized() : from.n;
  const Vec3 local(object.dot(to.t), object.dot(to.b), object.dot(to.n));
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<float>((local[c] + 1.0) * 127.5);
}

void PaintTexel(const TexelSource& t, const TexturedInput& input, const SourceTexture& s, int channels, float* out) {
  const Face& f = input.mesh->faces[t.face];
  float sample[4] = {255, 255, 255, 255};
  int sampled = 3;
  if (s.image != nullptr) {
    double u = 0, v = 0;
    for (size_t k = 0; k < 3; ++k) {
      u += t.barycentric[k] * (*input.texcoords)[f[k]][0];
      v += t.barycentric[k] * (*input.texcoords)[f[k]][1];
    }
    const auto& m = s.uv_transform;
    SampleBicubic(s, m[0] * u + m[1] * v + m[2], m[3] * u + m[4] * v + m[5], sample);
    sampled = s.image->channels;
  }
  if (s.normal_map != nullptr && sampled >= 3) ReexpressNormal(t, input, *s.normal_map, sample);
  if (channels == sampled) {
    std::copy(sample, sample + channels, out);
  } else {  // gray (+ alpha) widened
    std::fill(out, out + 3, sample[0]);
    if (channels == 4) out[3] = sample[1];
  }
  if (s.vertex_colors == nullptr) return;
  for (size_t c = 0; c < 3; ++c) {
    double vc = 0;
    for (size_t k = 0; k < 3; ++k) vc += t.barycentric[k] * (*s.vertex_colors)[f[k]][c];
    out[c] = static_cast<float>(out[c] * vc);
  }
}

}  // namespace

Image PaintAtlas(const TexelMap& map, const TexturedInput& input, const SourceTexture& source) {
  const int channels = PaintedChannels(source);
  const size_t n = map.texels.size();
  std::vector<float> color(n * static_cast<size_t>(channels), 0.0f);
  std::vector<bool> filled(n, false);
  for (size_t i = 0; i < n; ++i) {
    if (map.texels[i].face == kNoTexelFace) continue;
    PaintTexel(map.texels[i], input, source, channels, &color[i * static_cast<size_t>(channels)]);
    filled[i] = true;
  }
  Dilate(map.width, map.height, channels, map.dilation_passes, &color, &filled);
  FillRemaining(channels, &color, filled);
  Image out;
  out.width = static_cast<int>(map.width);
  out.height = static_cast<int>(map.height);
  out.channels = channels;
  out.pixels.resize(color.size());
  for (size_t i = 0; i < color.size(); ++i) {
    out.pixels[i] = static_cast<uint8_t>(std::clamp(std::lround(color[i]), 0L, 255L));
  }
  return out;
}

}  // namespace eqmesh::texture

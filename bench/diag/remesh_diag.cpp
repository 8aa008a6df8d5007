// Remesh diagnosis (developer tool, not part of the product build): where does a
// remesh's error sit, and at which level did it appear?
//
//   remesh_diag INPUT REMESH.srm [--png OUT.png] [--zoom N] [--top K] [--level L]
//               [--at X,Y,Z [--size S] [--strip OUT.png] [--view DX,DY,DZ] [--bad E]]
//
// Per finest face: the largest distance of its centroid and edge midpoints to the
// input (what Metro's remesh->input direction sees), its area, and whether it is
// folded against the input (normal opposed to the closest input face's). Prints
// how the squared error concentrates, the worst faces with their ancestors' errors
// level by level and their corners' kinds; --png renders six axis views coloured
// by error (folds magenta), --zoom N adds views around the N worst clusters;
// --strip renders the neighbourhood of --at (S diagonals wide) at every level
// and the input, --bad E showing only faces whose error exceeds E diagonals over
// the input in grey.
// Build: cmake --build build --target remesh_diag.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "mesh_io/mesh_io.h"
#include "mesh/semi_regular.h"
#include "mesh_io/semi_regular_io.h"
#include "mesh/triangle_bvh.h"

using namespace eqmesh;

namespace {

struct FaceInfo {
  double err = 0;   // max distance of sample points to the input
  double area = 0;
  bool folded = false;
};

FaceInfo Measure(const TriangleBvh& bvh, const Mesh& input, const Vec3& a, const Vec3& b, const Vec3& c) {
  FaceInfo fi;
  const Vec3 n = (b - a).cross(c - a);
  fi.area = 0.5 * n.norm();
  const Vec3 pts[4] = {(a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)};
  for (int i = 0; i < 4; ++i) {
    const ClosestPointResult cp = bvh.ClosestPoint(pts[i]);
    fi.err = std::max(fi.err, std::sqrt(cp.squared_distance));
    if (i == 0 && cp.found()) {
      const Face& g = input.faces[cp.face];
      const Vec3 m = (input.positions[g[1]] - input.positions[g[0]]).cross(input.positions[g[2]] - input.positions[g[0]]);
      fi.folded = m.dot(n) < 0.0;
    }
  }
  return fi;
}

struct Image {
  int w, h;
  std::vector<uint8_t> rgb;
  std::vector<float> z;
  Image(int w_, int h_) : w(w_), h(h_), rgb(3 * w_ * h_, 255), z(w_ * h_, 1e30f) {}
};

void Colour(double t, uint8_t* out) {  // t in [0,1]: blue -> green -> yellow -> red
  t = std::clamp(t, 0.0, 1.0);
  double r, g, b;
  if (t < 0.33) { r = 0; g = t / 0.33; b = 1 - t / 0.33; }
  else if (t < 0.66) { r = (t - 0.33) / 0.33; g = 1; b = 0; }
  else { r = 1; g = 1 - (t - 0.66) / 0.34; b = 0; }
  out[0] = static_cast<uint8_t>(255 * r);
  out[1] = static_cast<uint8_t>(255 * g);
  out[2] = static_cast<uint8_t>(255 * b);
}

// Orthographic view looking along -dir, up vector up, centred at c with half-size s.
double g_min_err = 0.0;
bool g_grey = false;
void Render(Image& img, int ox, int oy, int size, const Mesh& m, const std::vector<FaceInfo>& info,
            double err_lo, double err_hi, const Vec3& c, double s, const Vec3& dir, const Vec3& up) {
  const Vec3 zax = dir.normalized();
  const Vec3 xax = up.cross(zax).normalized();
  const Vec3 yax = zax.cross(xax);
  auto proj = [&](const Vec3& p, double* x, double* y, double* z) {
    const Vec3 q = p - c;
    *x = ox + (q.dot(xax) / s * 0.5 + 0.5) * size;
    *y = oy + (0.5 - q.dot(yax) / s * 0.5) * size;
    *z = -q.dot(zax);
  };
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const Vec3& a = m.positions[m.faces[f][0]];
    const Vec3& b = m.positions[m.faces[f][1]];
    const Vec3& cc = m.positions[m.faces[f][2]];
    Vec3 n = (b - a).cross(cc - a);
    if (n.norm() == 0) continue;
    if (!g_grey && info[f].err < g_min_err) continue;
    n.normalize();
    const double shade = 0.35 + 0.65 * std::abs(n.dot(zax));
    uint8_t col[3];
    if (g_grey) { col[0] = col[1] = col[2] = 200; }
    else if (info[f].folded) { col[0] = 255; col[1] = 0; col[2] = 255; }
    else {
      const double t = info[f].err > 0 ? (std::log(info[f].err) - std::log(err_lo)) / (std::log(err_hi) - std::log(err_lo)) : 0;
      Colour(t, col);
    }
    double x[3], y[3], z[3];
    proj(a, &x[0], &y[0], &z[0]);
    proj(b, &x[1], &y[1], &z[1]);
    proj(cc, &x[2], &y[2], &z[2]);
    const int x0 = std::max(ox, static_cast<int>(std::floor(std::min({x[0], x[1], x[2]}))));
    const int x1 = std::min(ox + size - 1, static_cast<int>(std::ceil(std::max({x[0], x[1], x[2]}))));
    const int y0 = std::max(oy, static_cast<int>(std::floor(std::min({y[0], y[1], y[2]}))));
    const int y1 = std::min(oy + size - 1, static_cast<int>(std::ceil(std::max({y[0], y[1], y[2]}))));
    const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0) continue;
    for (int py = y0; py <= y1; ++py) {
      for (int px = x0; px <= x1; ++px) {
        const double X = px + 0.5, Y = py + 0.5;
        const double w0 = ((x[1] - X) * (y[2] - Y) - (x[2] - X) * (y[1] - Y)) / area;
        const double w1 = ((x[2] - X) * (y[0] - Y) - (x[0] - X) * (y[2] - Y)) / area;
        const double w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const float zz = static_cast<float>(w0 * z[0] + w1 * z[1] + w2 * z[2]);
        const int idx = py * img.w + px;
        if (zz >= img.z[idx]) continue;
        img.z[idx] = zz;
        for (int k = 0; k < 3; ++k) img.rgb[3 * idx + k] = static_cast<uint8_t>(col[k] * shade);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: remesh_diag INPUT REMESH.srm [--png OUT] [--zoom N] [--top K] [--level L]\n");
    return 2;
  }
  std::string png, strip;
  Vec3 view_dir = Vec3::Zero();
  int zoom = 0, top = 12, level = -1, list_folds = 0;
  bool have_at = false;
  Vec3 at = Vec3::Zero();
  double at_size = 0.03, bad = 0.0;
  for (int i = 3; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--png")) png = argv[i + 1];
    else if (!std::strcmp(argv[i], "--zoom")) zoom = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--top")) top = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--level")) level = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--size")) at_size = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--strip")) strip = argv[i + 1];
    else if (!std::strcmp(argv[i], "--bad")) bad = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--folds")) list_folds = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--view")) std::sscanf(argv[i + 1], "%lf,%lf,%lf", &view_dir[0], &view_dir[1], &view_dir[2]);
    else if (!std::strcmp(argv[i], "--at")) {
      have_at = true;
      std::sscanf(argv[i + 1], "%lf,%lf,%lf", &at[0], &at[1], &at[2]);
    }
  }
  auto input = ReadMesh(argv[1]);
  if (!input.ok()) { std::fprintf(stderr, "%s\n", input.status().message().c_str()); return 1; }
  auto srm = ReadSemiRegular(argv[2]);
  if (!srm.ok()) { std::fprintf(stderr, "%s\n", srm.status().message().c_str()); return 1; }
  auto bvh = TriangleBvh::Build(*input);
  const SemiRegularHierarchy& h = srm->hierarchy;
  const int L = level < 0 ? h.levels() : level;
  const double diag = BoundingBoxDiagonal(*input);
  std::vector<std::vector<FaceInfo>> per_level(L + 1);
  for (int l = 0; l <= L; ++l) {
    const auto& faces = h.Faces(l);
    per_level[l].resize(faces.size());
    for (long f = 0; f < static_cast<long>(faces.size()); ++f) {
      per_level[l][f] = Measure(*bvh, *input, srm->positions[faces[f][0]], srm->positions[faces[f][1]],
                                srm->positions[faces[f][2]]);
    }
  }
  const auto& fin = per_level[L];
  std::vector<size_t> order(fin.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return fin[a].err * fin[a].err * fin[a].area > fin[b].err * fin[b].err * fin[b].area;
  });
  double total = 0, area = 0;
  size_t folded = 0;
  for (const FaceInfo& fi : fin) {
    total += fi.err * fi.err * fi.area;
    area += fi.area;
    folded += fi.folded;
  }
  std::printf("level %d: %zu faces, %zu folded, area-weighted rms(max-sample) %.3g diag -> %.2f dB\n", L, fin.size(),
              folded, std::sqrt(total / area) / diag, 20 * std::log10(diag / std::sqrt(total / area)));
  for (int l = 0; l <= L; ++l) {
    double t = 0, a = 0;
    size_t fo = 0;
    for (const FaceInfo& fi : per_level[l]) { t += fi.err * fi.err * fi.area; a += fi.area; fo += fi.folded; }
    std::printf("  level %d: %8zu faces, folded %6zu (%.3f%%), est %.2f dB\n", l, per_level[l].size(), fo,
                100.0 * static_cast<double>(fo) / static_cast<double>(per_level[l].size()), 20 * std::log10(diag / std::sqrt(t / a)));
  }
  double acc = 0;
  const double fracs[] = {0.0001, 0.001, 0.01, 0.1};
  size_t fi_idx = 0;
  for (size_t i = 0; i < order.size() && fi_idx < 4; ++i) {
    acc += fin[order[i]].err * fin[order[i]].err * fin[order[i]].area;
    if (static_cast<double>(i + 1) >= fracs[fi_idx] * static_cast<double>(order.size())) {
      std::printf("  worst %.2f%% of faces carry %.1f%% of the squared error\n", 100 * fracs[fi_idx], 100 * acc / total);
      ++fi_idx;
    }
  }
  // Folded faces, clustered.
  {
    std::vector<Vec3> fc;
    std::vector<int> cnt;
    for (size_t f = 0; f < fin.size(); ++f) {
      if (!fin[f].folded) continue;
      const Face& face = h.Faces(L)[f];
      const Vec3 c = (srm->positions[face[0]] + srm->positions[face[1]] + srm->positions[face[2]]) / 3.0;
      size_t k = 0;
      for (; k < fc.size(); ++k) if ((fc[k] - c).norm() < 0.01 * diag) break;
      if (k == fc.size()) { fc.push_back(c); cnt.push_back(0); }
      ++cnt[k];
    }
    std::printf("  %zu fold clusters:", fc.size());
    for (size_t k = 0; k < fc.size() && k < 40; ++k) std::printf(" %d@(%.3g,%.3g,%.3g)", cnt[k], fc[k][0], fc[k][1], fc[k][2]);
    std::printf("\n");
  }
  // Folded faces one by one: is the centroid's closest input face on the other
  // side of a thin part (corners agree with the face, the centroid does not)?
  const char* kind_names = "BNnb";
  for (size_t f = 0, shown = 0; f < fin.size() && static_cast<int>(shown) < list_folds; ++f) {
    if (!fin[f].folded) continue;
    ++shown;
    const Face& face = h.Faces(L)[f];
    const Vec3 p[3] = {srm->positions[face[0]], srm->positions[face[1]], srm->positions[face[2]]};
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    auto input_normal = [&](uint32_t g) {
      const Face& t = input->faces[g];
      return Vec3((input->positions[t[1]] - input->positions[t[0]]).cross(input->positions[t[2]] - input->positions[t[0]]).normalized());
    };
    const Vec3 c = (p[0] + p[1] + p[2]) / 3.0;
    const ClosestPointResult cc = bvh->ClosestPoint(c);
    const double longest = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    std::printf("fold %zu L%d at (%.4g,%.4g,%.4g): centroid dist %.2g diag, dot %.2f, longest edge %.2g diag; corners:", f, L,
                c[0], c[1], c[2], std::sqrt(cc.squared_distance) / diag, n.dot(input_normal(cc.face)), longest / diag);
    for (int i = 0; i < 3; ++i) {
      const ClosestPointResult ci = bvh->ClosestPoint(p[i]);
      std::printf(" [%c dist %.1g dot %.2f]", srm->kinds.empty() ? '?' : kind_names[static_cast<int>(srm->kinds[face[i]])],
                  std::sqrt(ci.squared_distance) / diag, n.dot(input_normal(ci.face)));
    }
    std::printf("\n");
  }
  // Worst faces with their ancestry.
  std::vector<Vec3> centres;
  for (int t = 0, i = 0; t < top && i < static_cast<int>(order.size()); ++i) {
    const size_t f = order[i];
    const Face& face = h.Faces(L)[f];
    const Vec3 c = (srm->positions[face[0]] + srm->positions[face[1]] + srm->positions[face[2]]) / 3.0;
    bool near = false;
    for (const Vec3& o : centres) near |= (o - c).norm() < 0.02 * diag;
    if (near) continue;
    centres.push_back(c);
    ++t;
    std::printf("#%d face %zu at (%.4g %.4g %.4g): err %.3g diag, area %.3g, folded %d, kinds %c%c%c; ancestors:", t, f,
                c[0], c[1], c[2], fin[f].err / diag, fin[f].area / (diag * diag), fin[f].folded,
                srm->kinds.empty() ? '?' : kind_names[static_cast<int>(srm->kinds[face[0]])],
                srm->kinds.empty() ? '?' : kind_names[static_cast<int>(srm->kinds[face[1]])],
                srm->kinds.empty() ? '?' : kind_names[static_cast<int>(srm->kinds[face[2]])]);
    size_t g = f;
    for (int l = L; l >= 0; --l) {
      std::printf(" L%d %.2g%s", l, per_level[l][g].err / diag, per_level[l][g].folded ? "F" : "");
      g /= 4;
    }
    std::printf("\n");
  }
  if (have_at && !strip.empty()) {
    const ClosestPointResult cp = bvh->ClosestPoint(at);
    const Face& g = input->faces[cp.face];
    Vec3 n = (input->positions[g[1]] - input->positions[g[0]]).cross(input->positions[g[2]] - input->positions[g[0]]);
    n.normalize();
    if (view_dir.norm() > 0) n = view_dir.normalized();
    const Vec3 up = std::abs(n.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX();
    const int size = 400;
    const int cols = 4, rows = (L + 1 + 1 + cols - 1) / cols;
    Image img(cols * size, rows * size);
    for (int l = 0; l <= L + 1; ++l) {
      Mesh m;
      if (l <= L) {
        m.positions = srm->positions;
        m.faces = h.Faces(l);
      } else {
        m = *input;  // last panel: the input itself
      }
      std::vector<FaceInfo> info = l <= L ? per_level[l] : std::vector<FaceInfo>(m.faces.size());
      if (bad > 0 && l <= L) {
        g_grey = true;
        Render(img, (l % cols) * size, (l / cols) * size, size, *input, std::vector<FaceInfo>(input->faces.size()), 1e-5 * diag, 1e-2 * diag, at, at_size * diag, n, up);
        g_grey = false;
        g_min_err = bad * diag;
      }
      Render(img, (l % cols) * size, (l / cols) * size, size, m, info, 1e-5 * diag, 1e-2 * diag, at, at_size * diag, n, up);
    }
    stbi_write_png(strip.c_str(), img.w, img.h, 3, img.rgb.data(), img.w * 3);
  }
  if (have_at) {
    centres.insert(centres.begin(), at);
    zoom = std::max(zoom, 1);
  }
  if (!png.empty()) {
    Mesh m;
    m.positions = srm->positions;
    m.faces = h.Faces(L);
    const int views = 6 + std::min<int>(zoom, static_cast<int>(centres.size()));
    const int size = 512;
    const int cols = std::min(views, 4);
    const int rows = (views + cols - 1) / cols;
    Image img(cols * size, rows * size);
    BoundingBox box = ComputeBoundingBox(*input);
    const Vec3 c = 0.5 * (box.min + box.max);
    const double s = 0.55 * (box.max - box.min).maxCoeff();
    const double lo = 1e-5 * diag, hi = 1e-2 * diag;
    const Vec3 dirs[6] = {Vec3::UnitZ(), -Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY()};
    const Vec3 ups[6] = {Vec3::UnitY(), Vec3::UnitY(), Vec3::UnitY(), Vec3::UnitY(), Vec3::UnitZ(), Vec3::UnitZ()};
    for (int v = 0; v < views; ++v) {
      const int ox = (v % cols) * size, oy = (v / cols) * size;
      if (v < 6) {
        Render(img, ox, oy, size, m, fin, lo, hi, c, s, dirs[v], ups[v]);
      } else {
        const Vec3& zc = centres[v - 6];
        // Look along the local input normal at the cluster.
        const ClosestPointResult cp = bvh->ClosestPoint(zc);
        const Face& g = input->faces[cp.face];
        Vec3 n = (input->positions[g[1]] - input->positions[g[0]]).cross(input->positions[g[2]] - input->positions[g[0]]);
        n.normalize();
        const Vec3 up = std::abs(n.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX();
        Render(img, ox, oy, size, m, fin, lo, hi, zc, at_size * diag, n, up);
      }
    }
    stbi_write_png(png.c_str(), img.w, img.h, 3, img.rgb.data(), img.w * 3);
    std::printf("wrote %s\n", png.c_str());
  }
  return 0;
}

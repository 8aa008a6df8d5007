// Writes the bundled sample (samples/meshes/blob.obj): a closed, genus-0, irregularly
// tessellated bumpy blob, small enough to ship and remesh in a second. The
// tessellation is an icosphere with tangential jitter so that it is not already
// semi-regular, and the shape has bumps at several scales like a sculpted object.
//
// usage: make_sample_mesh OUT.obj [subdivisions=4]
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

namespace {

struct P { double x, y, z; };

P Normalize(P p) {
  const double n = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  return {p.x / n, p.y / n, p.z / n};
}

// Deterministic hash noise in [-0.5, 0.5] (no std:: distributions: portable output).
double Jitter(uint32_t i, uint32_t salt) {
  uint64_t z = (static_cast<uint64_t>(i) << 32 | salt) + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) / 9007199254740992.0 - 0.5;
}

double Radius(const P& d) {
  return 1.0 + 0.18 * std::sin(3.0 * d.x) * std::cos(2.0 * d.y) + 0.07 * std::sin(7.0 * d.z + 1.0) +
         0.025 * std::cos(13.0 * d.x + 11.0 * d.y);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_sample_mesh OUT.obj [subdivisions]\n");
    return 2;
  }
  const int subdivisions = argc > 2 ? std::atoi(argv[2]) : 4;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<P> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::vector<uint32_t>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (P& p : v) p = Normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const std::pair<uint32_t, uint32_t> key(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(Normalize({v[a].x + v[b].x, v[a].y + v[b].y, v[a].z + v[b].z}));
      return mid[key] = static_cast<uint32_t>(v.size() - 1);
    };
    std::vector<std::vector<uint32_t>> g;
    for (auto& tri : f) {
      const uint32_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({a, tri[1], b});
      g.push_back({c, b, tri[2]});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  const double edge = 1.1 / (1 << subdivisions);
  for (uint32_t i = 0; i < v.size(); ++i) {
    P d = Normalize({v[i].x + edge * Jitter(i, 1), v[i].y + edge * Jitter(i, 2), v[i].z + edge * Jitter(i, 3)});
    const double r = Radius(d);
    v[i] = {r * d.x * 1.2, r * d.y, r * d.z * 0.9};
  }
  FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "make_sample_mesh: cannot write %s\n", argv[1]);
    return 1;
  }
  std::fprintf(out, "# eqmesh sample: bumpy blob, %zu vertices, %zu faces (samples/make_sample_mesh.cpp)\n",
               v.size(), f.size());
  for (const P& p : v) std::fprintf(out, "v %.7f %.7f %.7f\n", p.x, p.y, p.z);
  for (auto& tri : f) std::fprintf(out, "f %u %u %u\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
  std::fclose(out);
  return 0;
}

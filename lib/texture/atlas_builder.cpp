#include "texture/atlas_builder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "coding/decoder.h"

namespace eqmesh::texture {
namespace {

double TriangleArea(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

double EdgeLength(const std::vector<Vec3>& positions, const Face& f, int k) {
  return (positions[f[static_cast<size_t>((k + 1) % 3)]] - positions[f[static_cast<size_t>(k)]]).norm();
}

// Positions indexed like AtlasFaces' vertex numbers (base vertices, then kept).
std::vector<Vec3> AtlasFacePositions(const SemiRegularMesh& mesh) {
  std::vector<Vec3> p(mesh.positions.begin(), mesh.positions.begin() + mesh.hierarchy.NumVertices(0));
  p.insert(p.end(), mesh.kept_exactly.positions.begin(), mesh.kept_exactly.positions.end());
  return p;
}

// Face across each directed edge (u, v), found as the face holding (v, u).
std::map<std::pair<uint32_t, uint32_t>, uint32_t> DirectedEdgeFaces(const std::vector<Face>& faces) {
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> owner;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (size_t k = 0; k < 3; ++k) owner[{faces[f][k], faces[f][(k + 1) % 3]}] = f;
  }
  return owner;
}

// Corners of f ordered by the length of the edge they start, longest first.
std::array<int, 3> EdgesLongestFirst(const std::vector<Vec3>& positions, const Face& f) {
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return EdgeLength(positions, f, a) > EdgeLength(positions, f, b);
  });
  return order;
}

// Greedy pairing in face order: each unpaired face takes the unpaired face across
// its longest edge that has one, if their areas are within a factor 4 (one cell
// side serves both).
std::vector<AtlasCell> PairFaces(const std::vector<Face>& faces, const std::vector<Vec3>& positions,
                                 const std::vector<double>& areas) {
  const auto owner = DirectedEdgeFaces(faces);
  std::vector<bool> used(faces.size(), false);
  std::vector<AtlasCell> cells;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (used[f]) continue;
    used[f] = true;
    AtlasCell cell;
    cell.face_a = f;
    const std::array<int, 3> order = EdgesLongestFirst(positions, faces[f]);
    cell.edge = static_cast<uint8_t>(order[0]);
    for (int k : order) {
      const auto it = owner.find({faces[f][static_cast<size_t>((k + 1) % 3)], faces[f][static_cast<size_t>(k)]});
      if (it == owner.end() || used[it->second]) continue;
      const double ratio = areas[f] / std::max(areas[it->second], 1e-300);
      if (ratio > 4.0 || ratio < 0.25) continue;
      cell.paired = true;
      cell.face_b = it->second;
      cell.edge = static_cast<uint8_t>(k);
      used[it->second] = true;
      break;
    }
    cells.push_back(cell);
  }
  return cells;
}

// Cell area in the density's units: a pair fills its square, a single face half.
double CellSurface(const AtlasCell& c, const std::vector<double>& areas) {
  return c.paired ? areas[c.face_a] + areas[c.face_b] : 2.0 * areas[c.face_a];
}

// Packs cells of the given sides (sorted tallest first) in shelves of `width`;
// returns the height used and sets x, y, side.
uint64_t PackShelves(const std::vector<uint32_t>& order, const std::vector<uint32_t>& sides, uint32_t width,
                     std::vector<AtlasCell>* cells) {
  uint64_t x = 0, y = 0, shelf = 0;
  for (uint32_t i : order) {
    const uint32_t side = sides[i];
    if (x + side > width) {
      y += shelf;
      x = 0;
      shelf = 0;
    }
    if (shelf == 0) shelf = side;
    AtlasCell& c = (*cells)[i];
    c.x = static_cast<uint32_t>(x);
    c.y = static_cast<uint32_t>(y);
    c.side = side;
    x += side;
  }
  return y + shelf;
}

std::vector<uint32_t> SidesAt(double density, const std::vector<double>& surfaces, uint32_t gutter) {
  std::vector<uint32_t> sides(surfaces.size());
  for (size_t i = 0; i < surfaces.size(); ++i) {
    const double inner = std::floor(density * std::sqrt(surfaces[i]));
    sides[i] = static_cast<uint32_t>(std::min(inner, 65536.0)) + 2 * gutter + 2;
  }
  return sides;
}

bool Fits(double density, const std::vector<double>& surfaces, const AtlasBuildOptions& o,
          std::vector<AtlasCell>* cells) {
  const std::vector<uint32_t> sides = SidesAt(density, surfaces, o.gutter);
  std::vector<uint32_t> order(sides.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return sides[a] > sides[b]; });
  if (sides[order[0]] > std::min(o.width, o.height)) return false;
  return PackShelves(order, sides, o.width, cells) <= o.height;
}

}  // namespace

std::vector<double> AtlasFaceAreas(const SemiRegularMesh& mesh) {
  const SemiRegularHierarchy& h = mesh.hierarchy;
  const int level = h.levels();
  const std::vector<Face>& fine = h.Faces(level);
  const size_t per_base = fine.size() / std::max<size_t>(1, h.BaseFaces().size());
  std::vector<double> areas(h.BaseFaces().size(), 0.0);
  for (size_t f = 0; f < fine.size(); ++f) {
    areas[f / per_base] += TriangleArea(mesh.positions[fine[f][0]], mesh.positions[fine[f][1]], mesh.positions[fine[f][2]]);
  }
  for (const Face& f : mesh.kept_exactly.faces) {
    const auto& p = mesh.kept_exactly.positions;
    areas.push_back(TriangleArea(p[f[0]], p[f[1]], p[f[2]]));
  }
  return areas;
}

StatusOr<AtlasLayout> BuildAtlas(const SemiRegularMesh& mesh, const AtlasBuildOptions& options) {
  const std::vector<Face> faces = AtlasFaces(mesh);
  if (faces.empty()) return InvalidArgument("no faces to lay out in an atlas");
  const std::vector<double> areas = AtlasFaceAreas(mesh);
  AtlasLayout atlas;
  atlas.width = options.width;
  atlas.height = options.height;
  atlas.gutter = options.gutter;
  atlas.cells = PairFaces(faces, AtlasFacePositions(mesh), areas);
  std::vector<double> surfaces;
  for (const AtlasCell& c : atlas.cells) surfaces.push_back(CellSurface(c, areas));
  const double total = std::accumulate(surfaces.begin(), surfaces.end(), 0.0);
  if (!(total > 0) || !Fits(0.0, surfaces, options, &atlas.cells)) {
    return ResourceLimit(std::to_string(atlas.cells.size()) + " atlas cells do not fit a " +
                         std::to_string(options.width) + " x " + std::to_string(options.height) + " texture");
  }
  // Density in texels per unit length: the whole grid's side over the surface's
  // square root bounds it from above.
  double lo = 0.0, hi = std::sqrt(static_cast<double>(options.width) * options.height / total);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Fits(mid, surfaces, options, &atlas.cells) ? lo : hi) = mid;
  }
  Fits(lo, surfaces, options, &atlas.cells);
  return atlas;
}

}  // namespace eqmesh::texture

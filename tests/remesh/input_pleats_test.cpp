// FacesNearPleats: the input triangles the fold scan must not skip.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "remesh/input_pleats.h"

namespace eqmesh {
namespace {

// An n x n grid of unit squares in z = 0, two triangles each, facing +z.
Mesh Grid(int n) {
  Mesh m;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) m.positions.emplace_back(x, y, 0.0);
  }
  auto id = [n](int x, int y) { return static_cast<uint32_t>(y * (n + 1) + x); };
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      m.faces.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      m.faces.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  return m;
}

struct Incidence {
  std::vector<uint32_t> offsets, faces;
};

Incidence VertexFaces(const Mesh& m) {
  Incidence inc;
  inc.offsets.assign(m.positions.size() + 1, 0);
  for (const Face& f : m.faces) {
    for (uint32_t v : f) ++inc.offsets[v + 1];
  }
  for (size_t v = 0; v < m.positions.size(); ++v) inc.offsets[v + 1] += inc.offsets[v];
  inc.faces.resize(inc.offsets.back());
  std::vector<uint32_t> fill(inc.offsets.begin(), inc.offsets.end() - 1);
  for (uint32_t f = 0; f < m.faces.size(); ++f) {
    for (uint32_t v : m.faces[f]) inc.faces[fill[v]++] = f;
  }
  return inc;
}

size_t CountFlagged(const std::vector<uint8_t>& flags) {
  size_t n = 0;
  for (uint8_t f : flags) n += f;
  return n;
}

TEST(InputPleats, SmoothInputHasNone) {
  Mesh m = Grid(8);
  // A gentle bump: neighbouring faces stay far from 90 degrees apart.
  for (Vec3& p : m.positions) p.z() = 0.3 * std::sin(0.5 * p.x()) * std::cos(0.5 * p.y());
  const Incidence inc = VertexFaces(m);
  EXPECT_EQ(CountFlagged(FacesNearPleats(m, FaceCrossProducts(m), inc.offsets, inc.faces, 2)), 0u);
}

TEST(InputPleats, FoldedOverVertexFlagsItsStarAndTheRingsAround) {
  Mesh m = Grid(8);
  // Pull one interior vertex far across its neighbours: its star folds over.
  const uint32_t centre = 4 * 9 + 4;
  m.positions[centre] = Vec3(6.5, 4.2, 0.05);
  const Incidence inc = VertexFaces(m);
  const std::vector<uint8_t> near0 = FacesNearPleats(m, FaceCrossProducts(m), inc.offsets, inc.faces, 0);
  const std::vector<uint8_t> near1 = FacesNearPleats(m, FaceCrossProducts(m), inc.offsets, inc.faces, 1);
  // Every face of the folded star is flagged, faces far away are not.
  for (uint32_t q = inc.offsets[centre]; q < inc.offsets[centre + 1]; ++q) EXPECT_TRUE(near0[inc.faces[q]]);
  const uint32_t far_corner = 0;  // vertex (0, 0)
  for (uint32_t q = inc.offsets[far_corner]; q < inc.offsets[far_corner + 1]; ++q) {
    EXPECT_FALSE(near1[inc.faces[q]]);
  }
  // Each ring only adds faces.
  EXPECT_GT(CountFlagged(near1), CountFlagged(near0));
  for (size_t f = 0; f < m.faces.size(); ++f) {
    if (near0[f]) {
      EXPECT_TRUE(near1[f]);
    }
  }
}

}  // namespace
}  // namespace eqmesh

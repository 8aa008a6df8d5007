// A point of the parameter domain: a face of some level of the remesh plus
// barycentric coordinates in that face's reference (equilateral) triangle,
// ordered like the face's corners. Every input vertex carries one per level.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace eqmesh {

struct ParamPoint {
  uint32_t face = std::numeric_limits<uint32_t>::max();
  std::array<double, 3> bary{};
};

}  // namespace eqmesh

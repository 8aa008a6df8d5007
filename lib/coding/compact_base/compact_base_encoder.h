// Encoder of the compact base-mesh chunk (compact_base_model.h; ext_spec A.6).
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct CompactBaseEncoding {
  std::vector<uint8_t> bytes;
  Mesh decoded;                            // exactly what DecodeCompactBase returns
  std::vector<uint32_t> decoded_to_input;  // decoded vertex i was input vertex [i]
};

// Codes `mesh` with positions on a grid of 2^bits steps over its largest extent.
// kUnsupportedFeature when the mesh is not a manifold, consistently oriented
// triangle mesh with every vertex on a face (the caller then uses the Draco chunk),
// or when float32 cannot hold the grid.
StatusOr<CompactBaseEncoding> EncodeCompactBase(const Mesh& mesh, int bits);

}  // namespace eqmesh

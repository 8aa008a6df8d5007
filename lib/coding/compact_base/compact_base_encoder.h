// Encoder of the compact base-mesh chunk (compact_base_model.h; ext_spec A.6).
#pragma once

#include <cstdint>
#include <vector>

#include "coding/compact_base/compact_base_model.h"
#include "coding/compact_base/compact_positions.h"
#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct CompactBaseEncoding {
  std::vector<uint8_t> bytes;
  Mesh decoded;                            // exactly what DecodeCompactBase returns
  std::vector<uint32_t> decoded_to_input;  // decoded vertex i was input vertex [i]
};

// Codes `mesh` with positions on a grid of 2^depth - 1 steps over its largest extent
// (depth need not be whole: the chunk records the step, and indices use
// ceil(depth) bits).
// kUnsupportedFeature when the mesh is not a manifold, consistently oriented
// triangle mesh with every vertex on a face (the caller then uses the Draco chunk),
// or when float32 cannot hold the grid.
// tangential_quarters > 4 (positions-after layout only) codes positions in surface
// frames with a tangential step of tangential_quarters / 4 grid steps
// (compact_positions.h).
inline constexpr int kCompactMaxTangentialQuarters = 255;

struct CompactVariant {
  double depth = 0;
  int tangential_quarters = kGridTangentialQuarters;
  bool parallelogram_choice = false;  // axis grid, positions-after layout only (stream 1.7)
};

// The positions-after chunk for each variant, the connectivity traversed once.
StatusOr<std::vector<CompactBaseEncoding>> EncodeCompactBaseVariants(const Mesh& mesh,
                                                                     const std::vector<CompactVariant>& variants);

// Bytes of the positions-after chunk's connectivity alone: a lower bound on any
// compact chunk of `mesh` (the positions come on top).
StatusOr<size_t> CompactConnectivityBytes(const Mesh& mesh);

StatusOr<CompactBaseEncoding> EncodeCompactBase(const Mesh& mesh, double depth,
                                               CompactLayout layout = CompactLayout::kPositionsAfter,
                                               int tangential_quarters = kGridTangentialQuarters);

}  // namespace eqmesh

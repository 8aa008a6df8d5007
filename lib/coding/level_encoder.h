// Encoder half of the per-level coefficient coders (see level_decoder.h).
#pragma once

#include <cstdint>
#include <vector>

#include "coding/eq/eq_layout.h"
#include "coding/level_decoder.h"

namespace eqmesh {

// Codes the local coefficients of refinement j -> j+1 and returns the chunk;
// *reconstructed receives exactly what DecodeLevelCoefficients will return for it
// (the closed loop continues from those values). The EQ coder needs `eq_layout`,
// BuildEqLevelLayout(hierarchy, j), built once by the caller, which codes the
// level in every pass; the other coders take nullptr.
StatusOr<std::vector<uint8_t>> EncodeLevelCoefficients(const LevelCodingParams& params,
                                                       const SemiRegularHierarchy& hierarchy,
                                                       int j, const std::vector<Vec3>& local,
                                                       std::vector<Vec3>* reconstructed,
                                                       const EqLevelLayout* eq_layout);

}  // namespace eqmesh

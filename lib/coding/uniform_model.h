// The adaptive model of one component of the uniform baseline coder (level_decoder.h):
// shared by its encoder (level_encoder.cpp) and decoder (level_decoder.cpp) so the two
// halves cannot drift apart.
#pragma once

#include <array>

#include "coding/entropy/range_coder.h"
#include "coding/level_decoder.h"

namespace eqmesh::uniform_coder {

struct ComponentModel {
  AdaptiveBit zero;                        // q == 0
  std::array<AdaptiveBit, kUnaryLimit> unary;  // |q| - 1 > i, i < kUnaryLimit
};

}  // namespace eqmesh::uniform_coder

// EQ level decoder (Lavu, Choi, Baraniuk, SGP 2003; LoPresto, Ramchandran, Orchard,
// DCC 1997): reads one level's self-contained chunk and rebuilds its wavelet
// coefficients (normal, tangent, bitangent per odd vertex). Safe on hostile input:
// every loop is bounded by the layout, every allocation by its size, and a truncated
// or inconsistent chunk yields kCorruptStream.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "coding/eq/eq_layout.h"
#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// The coefficient count a level chunk declares (the first field of its side
// information, eq_model.h), or -1 when the chunk is too short to hold it. Cheap:
// the decoder compares it with the level before allocating the level's layout.
int64_t PeekEqLevelCount(const uint8_t* data, size_t size);

// True when the chunk is valid and its side information makes every coefficient
// of the level zero (UnpredictableQuantizer codes nothing for either stream) and
// no symbol follows (checked), so the level needs no layout. False when a class is coded or the side information does
// not decode (DecodeEqLevel then reports it).
StatusOr<bool> EqLevelCodesNothing(const uint8_t* data, size_t size, uint32_t count, bool tangential_context,
                                   int level);

// Coefficients in integer multiples of q0, indexed by odd index (not scan position).
// tangential_context: the chunk's tangential components are context-modelled
// (stream 1.3, header flag kTangentialContext), else one iid class (1.0-1.2).
StatusOr<std::vector<std::array<int64_t, 3>>> DecodeEqLevelQuanta(const EqLevelLayout& layout,
                                                                 const uint8_t* data, size_t size,
                                                                 bool tangential_context);

// Same, in world units: component c of odd vertex k is quanta[k][c] * q0.
StatusOr<std::vector<Vec3>> DecodeEqLevel(const EqLevelLayout& layout, const uint8_t* data,
                                          size_t size, double q0, bool tangential_context);

}  // namespace eqmesh

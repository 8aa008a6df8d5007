// Decoder of the compact base-mesh chunk (compact_base_model.h; ext_spec A.6).
// Every count is checked against its limit before anything is allocated for it, and
// every decoded index, face and position against the chunk's own promises: a
// truncated or hostile chunk is an error, never a crash or an unbounded loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "coding/compact_base/compact_base_model.h"
#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

// Decodes a compact chunk into positions and faces (the chunk's vertex order).
// `max_vertices` bounds the vertex count; `what` prefixes errors.
StatusOr<Mesh> DecodeCompactBase(const uint8_t* data, size_t size, uint32_t max_vertices,
                                 const std::string& what,
                                 CompactLayout layout = CompactLayout::kPositionsAfter);

}  // namespace eqmesh

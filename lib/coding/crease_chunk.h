// The crease chunk (stream 1.8, header flag kCreaseEdges): which base edges are
// tagged as creases (mesh/semi_regular.h), so the decoder's butterfly stencils
// follow them as the encoder's did.
//
// One adaptive binary decision per base edge, in the order the base's edges
// first appear walking its faces ((v0,v1), (v1,v2), (v2,v0) per face: the order
// of the level-0 odd vertices), range coded; the context is how many edges
// already tagged meet the edge's two ends (0, 1, 2 or more), since tags run in
// chains. ext_spec A.3.1 restates it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// The chunk for hierarchy.BaseCreases() (which must be non-empty).
std::vector<uint8_t> WriteCreaseChunk(const SemiRegularHierarchy& hierarchy);

// The tagged edges of `hierarchy`'s base, read from `size` bytes; every byte
// must be consumed. Corrupt-stream errors otherwise.
StatusOr<std::vector<Edge>> ReadCreaseChunk(const uint8_t* data, size_t size, const SemiRegularHierarchy& hierarchy);

}  // namespace eqmesh

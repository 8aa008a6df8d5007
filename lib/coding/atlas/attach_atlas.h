// Encoder side of the atlas chunk: the atlas is laid out after encoding (its cells
// are sized by the decoded surface), so it joins a finished stream as a container
// step that leaves every other chunk's bytes as they are.
#pragma once

#include <cstdint>
#include <vector>

#include "coding/atlas/atlas_layout.h"
#include "core/status.h"

namespace eqmesh {

// `stream` (a complete stream without an atlas) with the atlas chunk placed after
// its kept (or base) chunk, the header's kHasAtlas flag and atlas size set, and
// the minor version raised to the first one with atlases (1.4).
StatusOr<std::vector<uint8_t>> AttachAtlas(const std::vector<uint8_t>& stream, const AtlasLayout& atlas);

}  // namespace eqmesh

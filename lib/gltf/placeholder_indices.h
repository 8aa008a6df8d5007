// Works around tinygltf 2.7 (Debian bookworm), which refuses a primitive whose
// `indices` accessor has no bufferView — exactly the placeholder accessor the spec
// (like KHR_draco_mesh_compression) prescribes; tinygltf accepts that shape only for
// Draco, and only when built with its own Draco support.
//
// Before tinygltf parses a file, the `indices` of each primitive that carries
// EXT_normal_mesh_compression and whose indices accessor has no bufferView are
// removed from the JSON (GLB JSON chunk or .gltf text) and remembered; after
// parsing they are put back. Nothing else in the file changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"

namespace eqmesh::gltf {

struct DetachedIndices {
  size_t mesh = 0;
  size_t primitive = 0;
  int accessor = -1;
};

// The file's bytes with placeholder indices removed (unchanged bytes when there are
// none); `detached` receives what was removed. GLB and .gltf JSON are accepted.
StatusOr<std::vector<uint8_t>> DetachPlaceholderIndices(const std::vector<uint8_t>& file,
                                                        std::vector<DetachedIndices>* detached);

// Puts the removed indices back into the parsed model.
Status ReattachPlaceholderIndices(const std::vector<DetachedIndices>& detached, tinygltf::Model* model);

}  // namespace eqmesh::gltf

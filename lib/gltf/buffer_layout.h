// Buffer bookkeeping shared by the converter and the loader: appending data as new
// buffer views, dropping the accessors and buffer views that replaced primitives no
// longer use, and merging all buffers into one (the GLB BIN chunk).
//
// Only objects the caller names as candidates are ever dropped: an unreferenced
// buffer view of the input may belong to an extension we do not know, so it stays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include <tiny_gltf.h>

#include "core/status.h"

namespace eqmesh::gltf {

// Appends `size` bytes to buffer 0 (created when absent) at a 4-byte aligned offset,
// which satisfies every glTF component alignment, as a new buffer view with
// `target` (0 for none). Returns the buffer view index.
int AppendBufferView(tinygltf::Model* model, const uint8_t* data, size_t size, int target);

// The bytes of buffer view `view` ([first, first + byteLength)), proven to lie
// inside its buffer; `what` ("the stream's bufferView") names it in errors.
StatusOr<const uint8_t*> BufferViewData(const tinygltf::Model& model, int view, const std::string& what);

// Removes candidate accessors, then candidate buffer views, that nothing references
// any more, renumbering every reference we know of (primitives, morph targets,
// animations, skins, EXT_mesh_gpu_instancing, sparse accessors, images,
// KHR_draco_mesh_compression and EXT_normal_mesh_compression).
Status RemoveUnusedData(tinygltf::Model* model, const std::set<int>& candidate_accessors,
                        const std::set<int>& candidate_views);

// Rewrites the model with a single buffer (no URI) holding every buffer view's bytes,
// 4-byte aligned. Fails on views that point outside their buffer, and on models
// using EXT_meshopt_compression (its views address buffers directly).
Status MergeBuffers(tinygltf::Model* model);

}  // namespace eqmesh::gltf

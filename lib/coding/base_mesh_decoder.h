// Decoding of the base-mesh and kept-exactly chunks: Draco mesh buffers (Google
// Draco 1.5, edgebreaker or sequential connectivity, quantized positions).
//
// Departure from the seed paper (Lavu et al. 2003, sec. 4, which codes base
// connectivity with the Touma-Gotsman coder and scaling coefficients with a uniform
// quantizer + entropy coder): Draco's edgebreaker plays the TG coder's role and
// Draco's quantization + parallelogram prediction + entropy coding carries the
// scaling values; the encoder chooses the quantization depth by R-D (see
// base_mesh_encoder.h).
//
// Draco is treated as untrusted code on untrusted bytes: the element counts of the
// buffer's header are checked before Draco sees it (Draco 1.5.5 allocates for them
// unchecked: at most 2^17 + 64 per chunk byte, and the limits below), any
// exception is caught, and its output is checked (counts against limits, indices in
// range, no repeated corner, finite coordinates) before eqmesh uses it. Draco
// metadata is refused (kUnsupportedFeature).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct DracoMeshLimits {
  uint32_t max_vertices = 0;
  uint64_t max_faces = 0;
};

// Decodes one Draco mesh buffer into a Mesh (positions only). `what` prefixes errors.
StatusOr<Mesh> DecodeDracoMesh(const uint8_t* data, size_t size, const DracoMeshLimits& limits,
                               const std::string& what);

}  // namespace eqmesh

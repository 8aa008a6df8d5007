// Encoding of the base mesh (connectivity + level-0 scaling values) and of the
// kept-exactly components, with Google Draco (see base_mesh_decoder.h for the
// format and the departure from the seed paper's TG coder).
//
// R-D choice of the scaling-value depth (seed paper sec. 4 quantizes scaling
// coefficients "using variable bit rate" but does not say how; its future work asks
// for the R-D trade-off between scaling and wavelet coefficients). We try every
// Draco position depth b in [kBaseMinBits, kBaseMaxBits] and keep the b minimising
//     J(b) = R(b) + lambda_world * sum_i w_i * |x_i - x^_i(b)|^2
// with R in bits (the whole Draco chunk), x^ the Draco-decoded value and w_i the
// influence of base vertex i: the squared-norm energy, at the finest level, of the
// subdivision basis function of vertex i (BaseInfluenceWeights). That is the error
// a base displacement leaves when no finer detail corrects it: exact at low rates,
// an overestimate at high rates where closed-loop details absorb part of it.
// lambda_world is the level coder's lambda expressed per squared world unit.
//
// Draco reorders vertices and faces (edgebreaker traversal). The encoder learns the
// permutation with a probe encode that carries each vertex's input index as an
// extra integer attribute, then checks that the real stream decodes to the same
// connectivity and positions as the probe; the codec renumbers the semi-regular
// mesh to the decoded base order (semi_regular_reorder.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct DracoMeshEncoding {
  std::vector<uint8_t> bytes;                // the Draco buffer that goes in the stream
  Mesh decoded;                              // exactly what DecodeDracoMesh returns for it
  std::vector<uint32_t> decoded_to_input;    // decoded vertex i was input vertex [i]
  int bits = 0;                              // Draco position quantization depth
};

// One Draco encoding at a fixed depth, with the decoded result and vertex map.
// Picks the smallest of edgebreaker / sequential connectivity that round-trips.
StatusOr<DracoMeshEncoding> EncodeMeshWithDraco(const Mesh& mesh, int bits);

struct BaseRdReport {
  int bits = 0;
  double rate_bits = 0;
  double weighted_distortion = 0;
};

// The R-D choice described above. weights.size() == base.num_vertices().
StatusOr<DracoMeshEncoding> EncodeBaseMesh(const Mesh& base, const std::vector<double>& weights,
                                           double lambda_world, BaseRdReport* report = nullptr);

}  // namespace eqmesh

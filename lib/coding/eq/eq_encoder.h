// EQ level encoder (Lavu, Choi, Baraniuk, SGP 2003, Sec. 3.3 steps 5-16; LoPresto,
// Ramchandran, Orchard, DCC 1997): estimates the level's GGD side information,
// iterates the predictable / unpredictable partition to convergence (for the normal
// stream and, in 1.3 chunks, for the tangential one, eq_model.h: the two streams'
// classes are disjoint parts of the side information, so on a large level they
// iterate on two threads), then codes the level with the final side information,
// as the iteration's pass under it chose (the choices depend on the side
// information and the values alone, so the pass is not run again). Per
// coefficient the quantizer comes from the shared integer model (eq_model.h);
// the index is the one of {0, k-1, k} (k the dead-zone index) minimising
// J = R + lambda D, R from the bin frequencies.
//
// Departures: the partition can enter a short cycle (parameters of A give partition
// B and those of B give A); iteration stops at a fixed point, at a repeated
// partition or after max_iterations, and the level is coded with whichever of the
// side informations tried has the lowest estimated cost J = R + lambda D.
// The initial partition thresholds the unquantized causal neighbours
// at half the high-rate step sqrt(6 / (lambda ln 2)); (shape, sigma) of each class
// are the ML fit of the unquantized values over the table's shapes (not of the
// quantized ones); the predictable class sends a gain over the RMS sigma-hat (the
// ML fit of x / sigma-hat) instead of a sigma.
#pragma once

#include <cstdint>
#include <vector>

#include "coding/eq/eq_layout.h"
#include "coding/eq/eq_model.h"
#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct EqEncodeOptions {
  // lambda * q0^2 = 2^(lambda_code / 16); see EqLambdaCode.
  int32_t lambda_code = 0;
  // lambda of the tangential components = tangential_lambda_scale * lambda: below 1,
  // since their errors matter less (the stream header's tangential factor F divides
  // lambda; this multiplies it, so the level encoder passes 1 / F). The seed says it
  // used "100 lambda" for tangential components; with its J = R + lambda D that
  // would quantize them *finer*, so the intent is a 100x smaller lambda.
  double tangential_lambda_scale = 0.01;
  // Bound on the partition iterations (steps 7-16), per stream.
  int max_iterations = 12;
  // Context-modelled tangential components (stream 1.3); false writes 1.2 chunks.
  bool tangential_context = true;
};

struct EqEncodeStats {
  int iterations = 0;        // passes run (the level is coded as the best of them chose)
  bool converged = false;    // the partition reached a fixed point
  int cycle_length = 0;      // > 0: it entered a cycle of this period instead
  uint32_t last_change = 0;  // coefficients that changed class in the last iteration
  uint32_t unpredictable = 0;
  uint32_t nonzero_normal = 0;
  EqSideInfo side;
};

// lambda_code for a Lagrangian slope lambda (per squared world unit) and quantum q0.
int32_t EqLambdaCode(double lambda, double q0);

// Codes one level. local_coeffs[k] = (normal, tangent, bitangent) of odd vertex
// first_vertex + k, in world units. On success *reconstructed (if not null) holds
// exactly what DecodeEqLevel returns for the chunk, so a closed-loop encoder can
// continue from the decoder's geometry.
StatusOr<std::vector<uint8_t>> EncodeEqLevel(const EqLevelLayout& layout,
                                             const std::vector<Vec3>& local_coeffs, double q0,
                                             const EqEncodeOptions& options,
                                             std::vector<Vec3>* reconstructed,
                                             EqEncodeStats* stats = nullptr);

}  // namespace eqmesh

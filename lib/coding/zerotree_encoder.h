// Encoder half of coder 1 (zerotree) in the .eqm container: the coefficients it
// codes and the mapping between the encoder's R-D slope lambda and the zerotree's
// bit planes.
//
// Papers: Khodakovsky, Schröder, Sweldens 2000 (PGC) and Khodakovsky & Guskov 2003
// code all levels' coefficients in one embedded bit-plane stream (the seed paper's
// "ZT" baseline, Lavu, Choi, Baraniuk 2003 sec. 2.2). Such a stream cannot run in the
// per-level closed loop of the EQ coder (closed_loop.h): a level's reconstruction is
// only known once the whole stream, all levels, has been cut to its budget.
//
// Open loop, with one departure: the coefficients are those a *lossless* zerotree
// stream would need on top of the *decoded* base, i.e. the closed loop of
// closed_loop.h run with an identity level coder from the Draco-decoded level-0
// values. Level 0's details and frames therefore see the base quantization exactly
// (PGC analyses the true mesh, so its base error never goes away); finer levels are
// analysed on the true geometry, and the decoder's frames, computed from its own
// decoded (lossy) geometry, differ from them by the usual open-loop mismatch.
//
// lambda <-> plane: the finest level's coefficients are quantized with step
// 2^n quanta when the stream ends in bit plane n (zerotree_coder.h), and the
// high-rate rule of the uniform coder (level_decoder.h), lambda = 6 / (step^2 ln 2)
// per squared quantum, links the two:
//   plane(lambda)  = clamp(round(log2(6 / (lambda ln 2)) / 2), 0, 40)
//   lambda(plane)  = 6 / (4^plane ln 2)
// --lambda stops the stream after plane(lambda); a byte budget stops it wherever the
// budget ends and lambda(last plane) then chooses the base depth (equal slopes).
#pragma once

#include <cstdint>
#include <vector>

#include "coding/bitstream_shared.h"
#include "coding/closed_loop.h"
#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// coeffs[j][k]: local (normal, tangent, bitangent) detail of odd vertex k of
// refinement j, world units, as described above; `steps` are the hierarchy's.
StatusOr<std::vector<std::vector<Vec3>>> ZerotreeCoefficients(const ClosedLoopSteps& steps,
                                                              const AnalyzedLevels& truth,
                                                              const std::vector<Vec3>& decoded_base);

// The mapping above; lambda per squared quantum, > 0.
int ZerotreePlaneForLambda(double lambda);
double ZerotreeLambdaForPlane(int plane);

}  // namespace eqmesh

// Zerotree coefficients and the lambda <-> bit plane mapping (see zerotree_encoder.h).
#include "coding/zerotree_encoder.h"

#include <algorithm>
#include <cmath>

namespace eqmesh {

StatusOr<std::vector<std::vector<Vec3>>> ZerotreeCoefficients(const ClosedLoopSteps& steps,
                                                              const AnalyzedLevels& truth,
                                                              const std::vector<Vec3>& decoded_base) {
  std::vector<std::vector<Vec3>> coeffs;
  const LevelCoderFn lossless = [&coeffs](int, const std::vector<Vec3>& local, std::vector<Vec3>* out) {
    *out = local;
    coeffs.push_back(local);
    return StatusOr<std::vector<uint8_t>>(std::vector<uint8_t>{});
  };
  std::vector<std::vector<uint8_t>> unused;
  EQMESH_RETURN_IF_ERROR(
      EncodeLevelsClosedLoop(steps, truth, decoded_base, lossless, {}, &unused).status());
  return coeffs;
}

int ZerotreePlaneForLambda(double lambda) {
  const double plane = std::log2(6.0 / (lambda * std::log(2.0))) / 2.0;
  if (!(plane > 0)) return 0;  // also NaN: the finest plane
  return static_cast<int>(std::lround(std::min(plane, 40.0)));
}

double ZerotreeLambdaForPlane(int plane) {
  return 6.0 / (std::ldexp(1.0, 2 * plane) * std::log(2.0));
}

}  // namespace eqmesh

// PerturbVertices: fixed-magnitude displacement in a uniform random direction.
// Uniform directions by rejection (Marsaglia-style: draw in the cube, keep
// points inside the unit ball, normalise) rather than by angles, because
// sin/cos may differ in the last bit between libms while sqrt never does.
#include "tools/perturb.h"

#include <cmath>
#include <string>

#include "metrics/sample_rng.h"

namespace eqmesh {
namespace {

Vec3 RandomUnitVector(SampleRng* rng) {
  // Acceptance probability is pi/6 per try; 64 failures in a row has odds
  // below 1e-20, and the fallback only keeps the loop bounded.
  for (int attempt = 0; attempt < 64; ++attempt) {
    const Vec3 v(2.0 * rng->NextDouble() - 1.0, 2.0 * rng->NextDouble() - 1.0,
                 2.0 * rng->NextDouble() - 1.0);
    const double n2 = v.squaredNorm();
    // Reject the tiny core too: normalising a near-zero vector loses precision.
    if (n2 <= 1.0 && n2 > 1e-6) return v / std::sqrt(n2);
  }
  return Vec3(0.0, 0.0, 1.0);
}

}  // namespace

StatusOr<Mesh> PerturbVertices(const Mesh& mesh, double fraction, uint64_t seed) {
  if (!std::isfinite(fraction) || fraction < 0.0 || fraction > 1.0)
    return InvalidArgument("noise fraction must be in [0, 1], got " + std::to_string(fraction));
  if (mesh.faces.empty()) return InvalidMesh("mesh has no faces");
  for (const Face& f : mesh.faces)
    for (uint32_t v : f)
      if (v >= mesh.positions.size() || !mesh.positions[v].allFinite())
        return InvalidMesh("vertex " + std::to_string(v) + " is out of range or not finite");
  const double magnitude = fraction * BoundingBoxDiagonal(mesh);
  Mesh out = mesh;
  SampleRng rng(seed);
  for (Vec3& p : out.positions) p += magnitude * RandomUnitVector(&rng);
  return out;
}

}  // namespace eqmesh

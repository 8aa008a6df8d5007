// Appearance error between two coloured surfaces, measured with the geometry: on
// the same area-uniform samples as the Metro meter (surface_distance.h, same seed
// and blocks), the colour of each sample against the colour at its closest point
// on the other surface. RGB in [0, 255]; RMS over samples and channels per
// direction, the worse direction reported; PSNR = 20 log10(255 / RMS). The colour
// counterpart of the attribute-deviation measures of Roy, Foufou, Truchetet
// ("Mesh comparison using attribute deviation metric", IJIG 2004), with Metro's
// sampling in place of their vertex-based one.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "core/status.h"
#include "mesh/mesh.h"
#include "metrics/surface_distance.h"

namespace eqmesh {

// Colour of a surface at a point of face `face` with the given barycentric
// coordinates: RGB, each in [0, 255]. Called from several threads at once.
using SurfaceColor = std::function<std::array<double, 3>(uint32_t face, const std::array<double, 3>& barycentric)>;

struct ColorDistance {
  double rms_ab = 0.0, rms_ba = 0.0, rms = 0.0;  // per channel, rms = the worse direction
  double psnr_db = 0.0;                          // +inf when rms == 0
  uint64_t samples = 0;                          // per direction
};

// a is the original; options as for CompareSurfaces (same samples: same count,
// seed and blocks). Deterministic for any thread count.
StatusOr<ColorDistance> CompareColors(const Mesh& a, const SurfaceColor& color_a, const Mesh& b,
                                      const SurfaceColor& color_b, const CompareOptions& options = {});

}  // namespace eqmesh

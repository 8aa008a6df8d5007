// Conversion of detail vectors between world space and an odd vertex's local
// frame (normal, tangent, bitangent), as in Khodakovsky, Schröder, Sweldens 2000
// (PGC) and Khodakovsky & Guskov 2003: normal meshes put almost all of a detail
// into the normal component, so coding (n, t, b) separately pays off.
#pragma once

#include "wavelet/butterfly.h"

namespace eqmesh {

// (d . normal, d . tangent, d . bitangent): the frame is orthonormal, so this is
// the exact inverse of FromLocal up to rounding.
inline Vec3 ToLocal(const LocalFrame& frame, const Vec3& world) {
  return Vec3(world.dot(frame.normal), world.dot(frame.tangent), world.dot(frame.bitangent));
}

// local.x() * normal + local.y() * tangent + local.z() * bitangent.
inline Vec3 FromLocal(const LocalFrame& frame, const Vec3& local) {
  return local.x() * frame.normal + local.y() * frame.tangent + local.z() * frame.bitangent;
}

}  // namespace eqmesh

// Progress reporting for long work (remeshing a large mesh, a benchmark sweep).
// Library code reports through a callback; the CLI draws it on a terminal.
#pragma once

#include <functional>
#include <string>

namespace eqmesh {

// stage: short name ("simplify", "pierce level 3"); fraction in [0, 1].
using ProgressFn = std::function<void(const std::string& stage, double fraction)>;

inline void ReportProgress(const ProgressFn& fn, const std::string& stage, double fraction) {
  if (fn) fn(stage, fraction);
}

}  // namespace eqmesh

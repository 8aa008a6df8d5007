// One refinement j -> j+1 as both codec sides run it: the frames the level's
// details are expressed in (computed from decoded level-j values only) and the
// synthesis of level j+1 from level j and the decoded details.
//
// Unlifted (seed paper sec. 5, "unlifted butterfly wavelet"): level j+1 keeps the
// level-j values and appends odd value = butterfly prediction + detail, the detail
// given in the odd vertex's frame (lib/wavelet/butterfly.h: normal, tangent,
// bitangent). Lifted: delegated to lib/wavelet's RefinementStep.
#pragma once

#include <vector>

#include "coding/bitstream_shared.h"
#include "core/status.h"
#include "mesh/semi_regular.h"
#include "wavelet/butterfly.h"

namespace eqmesh {

Vec3 ToLocalFrame(const LocalFrame& f, const Vec3& v);
Vec3 FromLocalFrame(const LocalFrame& f, const Vec3& local);

class LevelSynthesis {
 public:
  LevelSynthesis(const SemiRegularHierarchy& hierarchy, int j, bitstream::TransformId transform);

  // Butterfly prediction of the odd vertices from level-j values (unlifted meaning).
  std::vector<Vec3> Predict(const std::vector<Vec3>& coarse) const;
  // Frames of the odd vertices from level-j values.
  std::vector<LocalFrame> Frames(const std::vector<Vec3>& coarse) const;
  // Level j+1 values from level-j values, the frames and the local details.
  Status Synthesize(const std::vector<Vec3>& coarse, const std::vector<LocalFrame>& frames,
                    const std::vector<Vec3>& local, std::vector<Vec3>* fine) const;

 private:
  const SemiRegularHierarchy* hierarchy_;
  int j_;
  bitstream::TransformId transform_;
  StencilTable stencils_;
};

}  // namespace eqmesh

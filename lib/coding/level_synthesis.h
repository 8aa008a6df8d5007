// One refinement j -> j+1 as the decoder runs it (and the closed-loop encoder
// mirrors it): the frames of the level's details come from the decoded level-j
// coarse values only (lib/wavelet/transform.h FramesForLevel), the details are
// turned to world space and RefinementStep::Synthesize builds level j+1.
// Unlifted: fine = coarse + (prediction + detail) for the odd vertices (seed paper
// sec. 5 "unlifted butterfly"); lifted: predict + update lifting step.
#pragma once

#include <vector>

#include "coding/bitstream_shared.h"
#include "core/status.h"
#include "mesh/semi_regular.h"
#include "wavelet/transform.h"

namespace eqmesh {

WaveletKind ToWaveletKind(bitstream::TransformId transform);

// kCorruptStream unless every decoded value of `level` is finite (a hostile stream
// may reconstruct infinities; nothing downstream may see them).
Status CheckFiniteLevel(const std::vector<Vec3>& values, int level);

class LevelSynthesis {
 public:
  LevelSynthesis(const SemiRegularHierarchy& hierarchy, int j, bitstream::TransformId transform)
      : step_(hierarchy, j, ToWaveletKind(transform)) {}

  const RefinementStep& step() const { return step_; }
  std::vector<LocalFrame> Frames(const std::vector<Vec3>& coarse) const {
    return FramesForLevel(step_, coarse);
  }
  // Level j+1 values from level-j coarse values, the frames and the local details.
  Status Synthesize(const std::vector<Vec3>& coarse, const std::vector<LocalFrame>& frames,
                    const std::vector<Vec3>& local, std::vector<Vec3>* fine) const;
  // Same result, the frames computed from `coarse` only for the odd vertices whose
  // local detail is non-zero: a zero detail is zero in any frame, and most of a
  // fine level's details quantize to zero. An empty `local` means all zero.
  Status Synthesize(const std::vector<Vec3>& coarse, const std::vector<Vec3>& local,
                    std::vector<Vec3>* fine) const;

 private:
  RefinementStep step_;
};

}  // namespace eqmesh

// The closed-loop level loop of the encoder, for both wavelet kinds.
//
// Per refinement j (coarse to fine), with c^_j the level-j values the decoder has:
//   frames  = FramesForLevel(step_j, c^_j)                     (decoder has these)
//   even0   = step_j.UndoUpdate(c^_j, d*_j)                    (unlifted: c^_j)
//   detail  = c*_{j+1}[odd] - step_j.Predict(even0)            (one closed-loop correction)
//   local   = ToLocal(frames, detail) -> level coder -> reconstruction r
//   c^_{j+1} = step_j.Synthesize(c^_j, FromLocal(frames, r))   (= the decoder)
// c*_j, d*_j are the open-loop analysis of the true mesh (unlifted: c*_j = level-j
// positions, update empty). For the unlifted kind the correction is exact: the
// detail is the true odd position minus the decoder's prediction. For the lifted
// kind the update that the decoder undoes uses the *quantized* details, so the
// prediction is formed from even0 (the open-loop details' update) — the one
// correction we apply; its residual error is Predict(Update(r - detail)), second
// order in the quantization error. Even values keep c^_j's error (as in any
// interpolating scheme, a coarse vertex's error is never revisited).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "coding/bitstream_shared.h"
#include "coding/level_synthesis.h"
#include "core/progress.h"
#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

// values[j] = c*_j (j = 0..J), details[j] = d*_j in world space (j = 0..J-1).
struct AnalyzedLevels {
  std::vector<std::vector<Vec3>> values;
  std::vector<std::vector<Vec3>> details;
};
AnalyzedLevels AnalyzeAllLevels(const SemiRegularHierarchy& hierarchy,
                                const std::vector<Vec3>& finest, bitstream::TransformId transform);

// Codes one level's local details; *reconstructed = what the decoder will get.
using LevelCoderFn = std::function<StatusOr<std::vector<uint8_t>>(
    int j, const std::vector<Vec3>& local, std::vector<Vec3>* reconstructed)>;

// The refinement steps of one hierarchy, one per level. Rate control runs many
// passes over the same hierarchy; sharing the steps builds each level's
// stencil tables once instead of once per pass (same sums, same order). The
// steps refer to `hierarchy`, which must outlive them.
class ClosedLoopSteps {
 public:
  ClosedLoopSteps(const SemiRegularHierarchy& hierarchy, bitstream::TransformId transform);
  const LevelSynthesis& level(int j) const { return levels_[static_cast<size_t>(j)]; }
  size_t size() const { return levels_.size(); }

 private:
  std::vector<LevelSynthesis> levels_;
};

// Runs the loop above from the decoded level-0 values; appends one chunk per level
// and returns the decoder's finest values.
StatusOr<std::vector<Vec3>> EncodeLevelsClosedLoop(const ClosedLoopSteps& steps, const AnalyzedLevels& truth,
                                                   std::vector<Vec3> decoded_base, const LevelCoderFn& coder,
                                                   const ProgressFn& progress,
                                                   std::vector<std::vector<uint8_t>>* chunks);

}  // namespace eqmesh

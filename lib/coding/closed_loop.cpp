#include "coding/closed_loop.h"

#include <string>

#include "wavelet/local_frame.h"

namespace eqmesh {

AnalyzedLevels AnalyzeAllLevels(const SemiRegularHierarchy& hierarchy,
                                const std::vector<Vec3>& finest, bitstream::TransformId transform) {
  const int levels = hierarchy.levels();
  AnalyzedLevels out;
  out.values.resize(levels + 1);
  out.details.resize(levels);
  out.values[levels] = finest;
  for (int j = levels - 1; j >= 0; --j) {
    const RefinementStep step(hierarchy, j, ToWaveletKind(transform));
    step.Analyze(out.values[j + 1], &out.values[j], &out.details[j]);
  }
  return out;
}

ClosedLoopSteps::ClosedLoopSteps(const SemiRegularHierarchy& hierarchy, bitstream::TransformId transform) {
  levels_.reserve(static_cast<size_t>(hierarchy.levels()));
  for (int j = 0; j < hierarchy.levels(); ++j) levels_.emplace_back(hierarchy, j, transform);
}

StatusOr<std::vector<Vec3>> EncodeLevelsClosedLoop(const ClosedLoopSteps& steps, const AnalyzedLevels& truth,
                                                   std::vector<Vec3> decoded, const LevelCoderFn& coder,
                                                   const ProgressFn& progress,
                                                   std::vector<std::vector<uint8_t>>* chunks) {
  const int levels = static_cast<int>(steps.size());
  for (int j = 0; j < levels; ++j) {
    ReportProgress(progress, "encode level " + std::to_string(j + 1), double(j) / levels);
    const LevelSynthesis& synthesis = steps.level(j);
    const RefinementStep& step = synthesis.step();
    const std::vector<LocalFrame> frames = synthesis.Frames(decoded);
    std::vector<Vec3> even, prediction;
    step.UndoUpdate(decoded, truth.details[j], &even);
    step.Predict(even, &prediction);
    const uint32_t first = step.num_coarse();
    std::vector<Vec3> local(step.num_odd());
    for (uint32_t k = 0; k < local.size(); ++k) {
      local[k] = ToLocal(frames[k], truth.values[j + 1][first + k] - prediction[k]);
    }
    std::vector<Vec3> reconstructed;
    EQMESH_ASSIGN_OR_RETURN(std::vector<uint8_t> chunk, coder(j, local, &reconstructed));
    chunks->push_back(std::move(chunk));
    std::vector<Vec3> fine;
    EQMESH_RETURN_IF_ERROR(synthesis.Synthesize(decoded, frames, reconstructed, &fine));
    decoded = std::move(fine);
  }
  return decoded;
}

}  // namespace eqmesh

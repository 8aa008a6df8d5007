#include "coding/level_synthesis.h"

#include <optional>
#include <string>

#include "wavelet/local_frame.h"

namespace eqmesh {

WaveletKind ToWaveletKind(bitstream::TransformId transform) {
  return transform == bitstream::TransformId::kLifted ? WaveletKind::kLifted : WaveletKind::kUnlifted;
}

Status CheckFiniteLevel(const std::vector<Vec3>& values, int level) {
  for (const Vec3& v : values) {
    if (!v.allFinite()) {
      return CorruptStream("eqm level " + std::to_string(level) + " decodes to non-finite positions");
    }
  }
  return Status::Ok();
}

Status LevelSynthesis::Synthesize(const std::vector<Vec3>& coarse,
                                  const std::vector<LocalFrame>& frames,
                                  const std::vector<Vec3>& local, std::vector<Vec3>* fine) const {
  const uint32_t odd = step_.num_odd();
  if (coarse.size() != step_.num_coarse() || frames.size() != odd || local.size() != odd) {
    return InternalError("level synthesis size mismatch at level " + std::to_string(step_.level()));
  }
  std::vector<Vec3> details(odd);
  for (uint32_t k = 0; k < odd; ++k) details[k] = FromLocal(frames[k], local[k]);
  step_.Synthesize(coarse, details, fine);
  return Status::Ok();
}

// Exactly the frames version: a zero local detail gives a world detail of +0 or
// -0 per coordinate, and both leave prediction + detail and the lifting sums
// unchanged (a butterfly prediction, a sum started at +0, is never -0).
Status LevelSynthesis::Synthesize(const std::vector<Vec3>& coarse, const std::vector<Vec3>& local,
                                  std::vector<Vec3>* fine) const {
  const uint32_t odd = step_.num_odd();
  if (coarse.size() != step_.num_coarse() || (!local.empty() && local.size() != odd)) {
    return InternalError("level synthesis size mismatch at level " + std::to_string(step_.level()));
  }
  if (local.empty()) {
    step_.Synthesize(coarse, local, fine);
    return Status::Ok();
  }
  std::vector<Vec3> details(odd, Vec3::Zero());
  std::optional<OddFrames> frames;
  for (uint32_t k = 0; k < odd; ++k) {
    if (local[k].x() == 0.0 && local[k].y() == 0.0 && local[k].z() == 0.0) continue;
    if (!frames) frames.emplace(step_.predictor(), coarse);
    details[k] = FromLocal(frames->Frame(k), local[k]);
  }
  step_.Synthesize(coarse, details, fine);
  return Status::Ok();
}

}  // namespace eqmesh

#include "coding/level_synthesis.h"

namespace eqmesh {

Vec3 ToLocalFrame(const LocalFrame& f, const Vec3& v) {
  return Vec3(f.normal.dot(v), f.tangent.dot(v), f.bitangent.dot(v));
}

Vec3 FromLocalFrame(const LocalFrame& f, const Vec3& local) {
  return local[0] * f.normal + local[1] * f.tangent + local[2] * f.bitangent;
}

LevelSynthesis::LevelSynthesis(const SemiRegularHierarchy& hierarchy, int j,
                               bitstream::TransformId transform)
    : hierarchy_(&hierarchy), j_(j), transform_(transform),
      stencils_(BuildButterflyStencils(hierarchy, j)) {}

std::vector<Vec3> LevelSynthesis::Predict(const std::vector<Vec3>& coarse) const {
  std::vector<Vec3> prediction;
  ApplyStencils(stencils_, coarse, &prediction);
  return prediction;
}

std::vector<LocalFrame> LevelSynthesis::Frames(const std::vector<Vec3>& coarse) const {
  return ComputeOddFrames(*hierarchy_, j_, stencils_, coarse);
}

Status LevelSynthesis::Synthesize(const std::vector<Vec3>& coarse,
                                  const std::vector<LocalFrame>& frames,
                                  const std::vector<Vec3>& local, std::vector<Vec3>* fine) const {
  const uint32_t odd = hierarchy_->NumOddVertices(j_);
  if (coarse.size() != hierarchy_->NumVertices(j_) || frames.size() != odd || local.size() != odd) {
    return InternalError("level synthesis size mismatch at level " + std::to_string(j_));
  }
  if (transform_ != bitstream::TransformId::kUnlifted) {
    return UnsupportedFeature("lifted transform not available in this build");
  }
  const std::vector<Vec3> prediction = Predict(coarse);
  *fine = coarse;
  fine->reserve(hierarchy_->NumVertices(j_ + 1));
  for (uint32_t k = 0; k < odd; ++k) fine->push_back(prediction[k] + FromLocalFrame(frames[k], local[k]));
  return Status::Ok();
}

}  // namespace eqmesh

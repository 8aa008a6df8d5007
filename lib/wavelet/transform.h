// Butterfly wavelet transform over a semi-regular hierarchy, unlifted
// (interpolating: Zorin, Schröder, Sweldens 1996 predictor only) or lifted
// (predict + update: Schröder & Sweldens 1995, Sweldens 1998).
//
// Both sides of the codec use the same objects: the encoder runs Analyze (or its
// closed-loop variant built from UndoUpdate/Predict), the decoder Synthesize.
// Everything is built from connectivity only; see transform.cpp for the
// normative update weights and the frame rule.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/status.h"
#include "mesh/semi_regular.h"
#include "wavelet/butterfly.h"

namespace eqmesh {

// Stream value: never renumber.
enum class WaveletKind : uint8_t { kUnlifted = 0, kLifted = 1 };

// Refinement j -> j+1 of a hierarchy. Holds a pointer to `hierarchy`, which must
// outlive the step. Coarse vectors have NumVertices(j) entries, detail vectors
// NumOddVertices(j) (world space, odd vertex NumVertices(j) + k at index k),
// fine vectors NumVertices(j+1); callers must pass at least these sizes.
class RefinementStep {
 public:
  RefinementStep(const SemiRegularHierarchy& hierarchy, int j, WaveletKind kind);
  ~RefinementStep();
  RefinementStep(RefinementStep&&) = default;

  int level() const { return j_; }
  WaveletKind kind() const { return kind_; }
  const SemiRegularHierarchy& hierarchy() const { return *hierarchy_; }
  uint32_t num_coarse() const { return hierarchy_->NumVertices(j_); }
  uint32_t num_odd() const { return hierarchy_->NumOddVertices(j_); }

  // Butterfly prediction stencils of the odd vertices (indices: level-j vertices),
  // built on first use. Until then Predict and Synthesize build each stencil as
  // they apply it (same sums, same order), which a single pass prefers.
  const StencilTable& stencils() const;
  // The stencils one at a time (built on first use).
  const ButterflyPredictor& predictor() const;
  // Lifting update: row v lists (odd index k, weight) with coarse_v = even_v +
  // sum weight * detail_k. Empty rows for the unlifted kind.
  const StencilTable& update() const;

  // fine -> coarse values (lifted: updated scaling values) and world details
  // (fine odd minus the prediction from the fine mesh's level-j positions).
  void Analyze(const std::vector<Vec3>& fine, std::vector<Vec3>* coarse,
               std::vector<Vec3>* details) const;
  // Exact inverse of Analyze (up to rounding). Empty `details` stand for all zero.
  void Synthesize(const std::vector<Vec3>& coarse, const std::vector<Vec3>& details,
                  std::vector<Vec3>* fine) const;

  // Level-j positions from coarse values and this level's details: lifted undoes
  // the update, unlifted copies. These are the positions predictions are made from.
  // Empty `details` stand for all zero.
  void UndoUpdate(const std::vector<Vec3>& coarse, const std::vector<Vec3>& details,
                  std::vector<Vec3>* even) const;
  // even -> prediction of every odd vertex (num_odd entries).
  void Predict(const std::vector<Vec3>& even, std::vector<Vec3>* predicted) const;

 private:
  void ApplyUpdate(const std::vector<Vec3>& details, double sign, std::vector<Vec3>* values) const;

  const SemiRegularHierarchy* hierarchy_;
  int j_;
  WaveletKind kind_;
  mutable std::optional<StencilTable> stencils_;
  mutable std::unique_ptr<ButterflyPredictor> predictor_;
  mutable std::optional<StencilTable> update_;  // update(): built on first use
};

// Frames in which the details of refinement j -> j+1 are coded. Normative rule:
// ComputeOddFrames on the level-j *coarse values as transmitted* (for the lifted
// kind, before the update is undone), because the decoder has exactly these
// before it decodes the level's details. For the unlifted kind the coarse values
// are the level-j positions, so the frames are the remesher's piercing frames.
std::vector<LocalFrame> FramesForLevel(const RefinementStep& step,
                                       const std::vector<Vec3>& coarse_values);

struct WaveletCoefficients {
  std::vector<Vec3> scaling;                // NumVertices(0) entries
  std::vector<std::vector<Vec3>> details;   // details[j][k]: world space, refinement j -> j+1
};

// Full analysis over all levels; finest_positions has NumVertices(levels())
// entries (extra ones are ignored; with fewer, empty coefficients are returned).
WaveletCoefficients ForwardTransform(const SemiRegularHierarchy& hierarchy,
                                     const std::vector<Vec3>& finest_positions, WaveletKind kind);

// Checks that `coefficients` has the sizes `hierarchy` implies for synthesis up
// to max_level (clamped to [0, levels()]): details of later levels may be absent,
// so a progressive decoder can synthesise what it has.
Status ValidateCoefficients(const SemiRegularHierarchy& hierarchy,
                            const WaveletCoefficients& coefficients, int max_level);

// Synthesis up to level max_level (clamped to [0, levels()]); returns
// NumVertices(max_level) positions. For the unlifted kind these are exactly the
// level's positions; for the lifted kind, level max_level's scaling values (a
// smoothed approximation). Returns an empty vector if ValidateCoefficients fails.
std::vector<Vec3> InverseTransform(const SemiRegularHierarchy& hierarchy,
                                   const WaveletCoefficients& coefficients, WaveletKind kind,
                                   int max_level);

}  // namespace eqmesh

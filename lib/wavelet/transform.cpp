// Butterfly wavelet transform: unlifted and lifted, one refinement at a time.
//
// Papers: Zorin, Schröder, Sweldens 1996 (the predictor, see butterfly.cpp);
// Schröder & Sweldens 1995 "Spherical wavelets" and Sweldens 1998 (lifting:
// predict then update, inverted by running the steps backwards with opposite
// signs); Khodakovsky, Schröder, Sweldens 2000 (PGC: butterfly details coded in a
// local frame); Khodakovsky & Guskov 2003 (normal meshes use the unlifted
// transform so details stay purely normal).
//
// NORMATIVE (the decoder follows this):
//  U1 Update weight of odd vertex m (on edge (a, b)) at its endpoint v:
//       w_{v,m} = F_m / (8 F_v),
//     F_m = number of level-(j+1) faces containing m (6 on an interior edge, 3 on
//     a boundary edge), F_v = number of level-j faces containing v. This is
//     Schröder–Sweldens' vanishing-moment choice w = I_m / (2 I_v) with each
//     scaling-function integral I replaced by its incident face count times the
//     level's face area (1/4 per level) — the area-free variant, so it depends on
//     connectivity only: 1/8 for regular vertices, 3/(4k) at interior valence k.
//     Departure: the papers integrate true areas; we keep the codec geometry-free.
//  U2 Lifted analysis: d_k = x_odd(k) - P(x_even)(k); then
//     coarse_v = x_v + Σ_k w_{v,k} d_k, summed in increasing k. Synthesis undoes
//     it in the same order: even_v = coarse_v - Σ_k w_{v,k} d_k; x_odd = P(even) + d.
//  U3 Frames of refinement j -> j+1: ComputeOddFrames on the level-j coarse
//     values as transmitted (see FramesForLevel in transform.h).
#include "wavelet/transform.h"

#include <algorithm>
#include <memory>
#include <string>

namespace eqmesh {
namespace {

std::vector<uint32_t> IncidentFaceCounts(const std::vector<Face>& faces, uint32_t num_vertices) {
  std::vector<uint32_t> counts(num_vertices, 0);
  for (const Face& f : faces) {
    for (uint32_t v : f) {
      if (v < num_vertices) ++counts[v];
    }
  }
  return counts;
}

// Rule U1 as a CSR table over the coarse vertices, rows in increasing odd index.
StencilTable BuildUpdateTable(const SemiRegularHierarchy& h, int j) {
  const uint32_t num_coarse = h.NumVertices(j), num_odd = h.NumOddVertices(j);
  const std::vector<uint32_t> coarse_faces = IncidentFaceCounts(h.Faces(j), num_coarse);
  const std::vector<uint32_t> fine_faces = IncidentFaceCounts(h.Faces(j + 1), h.NumVertices(j + 1));
  StencilTable table;
  table.offsets.assign(static_cast<size_t>(num_coarse) + 1, 0);
  for (const Edge& e : h.OddEdges(j)) {
    ++table.offsets[e[0] + 1];
    ++table.offsets[e[1] + 1];
  }
  for (uint32_t v = 0; v < num_coarse; ++v) table.offsets[v + 1] += table.offsets[v];
  table.indices.resize(table.offsets.back());
  table.weights.resize(table.offsets.back());
  std::vector<uint32_t> cursor(table.offsets.begin(), table.offsets.end() - 1);
  for (uint32_t k = 0; k < num_odd; ++k) {
    const double f_m = static_cast<double>(fine_faces[num_coarse + k]);
    for (uint32_t v : h.OddEdge(j, k)) {
      // Every odd edge comes from a face, so F_v >= 1.
      const uint32_t slot = cursor[v]++;
      table.indices[slot] = k;
      table.weights[slot] = f_m / (8.0 * static_cast<double>(coarse_faces[v]));
    }
  }
  return table;
}

bool AllZero(const std::vector<Vec3>& values, uint32_t count) {
  for (uint32_t k = 0; k < count; ++k) {
    if (values[k].x() != 0.0 || values[k].y() != 0.0 || values[k].z() != 0.0) return false;
  }
  return true;
}

}  // namespace

RefinementStep::RefinementStep(const SemiRegularHierarchy& hierarchy, int j, WaveletKind kind)
    : hierarchy_(&hierarchy), j_(j), kind_(kind) {}

RefinementStep::~RefinementStep() = default;

const StencilTable& RefinementStep::stencils() const {
  if (!stencils_) stencils_ = BuildButterflyStencils(*hierarchy_, j_);
  return *stencils_;
}

const ButterflyPredictor& RefinementStep::predictor() const {
  if (!predictor_) predictor_ = std::make_unique<ButterflyPredictor>(*hierarchy_, j_);
  return *predictor_;
}

// Built on first use: a decoder whose level details are all zero never needs it.
const StencilTable& RefinementStep::update() const {
  if (!update_) {
    if (kind_ == WaveletKind::kLifted) {
      update_ = BuildUpdateTable(*hierarchy_, j_);
    } else {
      update_.emplace();
      update_->offsets.assign(static_cast<size_t>(num_coarse()) + 1, 0);
    }
  }
  return *update_;
}

void RefinementStep::ApplyUpdate(const std::vector<Vec3>& details, double sign,
                                 std::vector<Vec3>* values) const {
  // Undoing an update of all-zero details is skipped: each sum is +0, and
  // x - (+0) == x for every x, -0 included, so the loop would change nothing.
  // (Adding +0 would turn -0 into +0, so analysis always runs the loop.)
  if (sign < 0.0 && (details.empty() || AllZero(details, num_odd()))) return;
  const StencilTable& table = update();
  for (uint32_t v = 0; v < num_coarse(); ++v) {
    Vec3 sum = Vec3::Zero();
    for (uint32_t i = table.offsets[v]; i < table.offsets[v + 1]; ++i) {
      sum += table.weights[i] * details[table.indices[i]];
    }
    (*values)[v] += sign * sum;
  }
}

void RefinementStep::Predict(const std::vector<Vec3>& even, std::vector<Vec3>* predicted) const {
  if (stencils_) {
    ApplyStencils(*stencils_, even, predicted);
    return;
  }
  const ButterflyPredictor& p = predictor();
  predicted->resize(num_odd());
  for (uint32_t k = 0; k < num_odd(); ++k) (*predicted)[k] = p.Stencil(k).Apply(even);
}

void RefinementStep::UndoUpdate(const std::vector<Vec3>& coarse, const std::vector<Vec3>& details,
                                std::vector<Vec3>* even) const {
  even->assign(coarse.begin(), coarse.begin() + num_coarse());
  if (kind_ == WaveletKind::kLifted) ApplyUpdate(details, -1.0, even);
}

void RefinementStep::Analyze(const std::vector<Vec3>& fine, std::vector<Vec3>* coarse,
                             std::vector<Vec3>* details) const {
  Predict(fine, details);
  const uint32_t n = num_coarse();
  for (uint32_t k = 0; k < num_odd(); ++k) (*details)[k] = fine[n + k] - (*details)[k];
  coarse->assign(fine.begin(), fine.begin() + n);
  if (kind_ == WaveletKind::kLifted) ApplyUpdate(*details, 1.0, coarse);
}

// The odd values are written straight after the even ones: the predictions read
// only fine[0, num_coarse()), so no separate prediction array is needed. Empty
// details leave the prediction as is, which is what adding +0 gives (a stencil
// sum starts at +0, so it is never -0).
void RefinementStep::Synthesize(const std::vector<Vec3>& coarse, const std::vector<Vec3>& details,
                                std::vector<Vec3>* fine) const {
  const uint32_t n = num_coarse();
  fine->reserve(static_cast<size_t>(n) + num_odd());
  UndoUpdate(coarse, details, fine);
  fine->resize(static_cast<size_t>(n) + num_odd());
  Vec3* odd = fine->data() + n;
  if (stencils_) {
    const StencilTable& t = *stencils_;
    for (uint32_t k = 0; k < num_odd(); ++k) {
      Vec3 sum = Vec3::Zero();
      for (uint32_t i = t.offsets[k]; i < t.offsets[k + 1]; ++i) sum += t.weights[i] * (*fine)[t.indices[i]];
      odd[k] = details.empty() ? sum : Vec3(sum + details[k]);
    }
    return;
  }
  const ButterflyPredictor& p = predictor();
  for (uint32_t k = 0; k < num_odd(); ++k) {
    const Vec3 predicted = p.Stencil(k).Apply(*fine);
    odd[k] = details.empty() ? predicted : Vec3(predicted + details[k]);
  }
}

std::vector<LocalFrame> FramesForLevel(const RefinementStep& step,
                                       const std::vector<Vec3>& coarse_values) {
  return ComputeOddFrames(step.hierarchy(), step.level(), step.stencils(), coarse_values);
}

WaveletCoefficients ForwardTransform(const SemiRegularHierarchy& hierarchy,
                                     const std::vector<Vec3>& finest_positions, WaveletKind kind) {
  WaveletCoefficients out;
  if (finest_positions.size() < hierarchy.NumVertices(hierarchy.levels())) return out;
  out.details.resize(static_cast<size_t>(hierarchy.levels()));
  std::vector<Vec3> current(finest_positions.begin(),
                            finest_positions.begin() + hierarchy.NumVertices(hierarchy.levels()));
  for (int j = hierarchy.levels() - 1; j >= 0; --j) {
    std::vector<Vec3> coarse;
    RefinementStep(hierarchy, j, kind).Analyze(current, &coarse, &out.details[j]);
    current = std::move(coarse);
  }
  out.scaling = std::move(current);
  return out;
}

Status ValidateCoefficients(const SemiRegularHierarchy& hierarchy,
                            const WaveletCoefficients& coefficients, int max_level) {
  max_level = std::clamp(max_level, 0, hierarchy.levels());
  if (coefficients.scaling.size() != hierarchy.NumVertices(0)) {
    return InvalidArgument("wavelet transform: " + std::to_string(coefficients.scaling.size()) +
                           " scaling coefficients for " + std::to_string(hierarchy.NumVertices(0)) +
                           " base vertices");
  }
  if (coefficients.details.size() < static_cast<size_t>(max_level)) {
    return InvalidArgument("wavelet transform: details for " +
                           std::to_string(coefficients.details.size()) + " levels, " +
                           std::to_string(max_level) + " needed");
  }
  for (int j = 0; j < max_level; ++j) {
    if (coefficients.details[j].size() != hierarchy.NumOddVertices(j)) {
      return InvalidArgument("wavelet transform: level " + std::to_string(j) + " has " +
                             std::to_string(coefficients.details[j].size()) + " details for " +
                             std::to_string(hierarchy.NumOddVertices(j)) + " odd vertices");
    }
  }
  return Status::Ok();
}

std::vector<Vec3> InverseTransform(const SemiRegularHierarchy& hierarchy,
                                   const WaveletCoefficients& coefficients, WaveletKind kind,
                                   int max_level) {
  max_level = std::clamp(max_level, 0, hierarchy.levels());
  if (!ValidateCoefficients(hierarchy, coefficients, max_level).ok()) return {};
  std::vector<Vec3> current = coefficients.scaling;
  for (int j = 0; j < max_level; ++j) {
    std::vector<Vec3> fine;
    RefinementStep(hierarchy, j, kind).Synthesize(current, coefficients.details[j], &fine);
    current = std::move(fine);
  }
  return current;
}

}  // namespace eqmesh

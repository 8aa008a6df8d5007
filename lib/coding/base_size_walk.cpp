// Base-size walk: see base_size_walk.h.
#include "coding/base_size_walk.h"

#include <cmath>
#include <utility>

namespace eqmesh {
namespace {

BaseSizeTry EncodeAtBaseSize(const Mesh& input, RemeshOptions remesh, const EncodeOptions& options,
                             size_t base_vertices) {
  BaseSizeTry t;
  t.base_vertices = base_vertices;
  remesh.base_vertices = static_cast<int>(base_vertices);
  remesh.levels = -1;
  StatusOr<SemiRegularMesh> mesh = Remesh(input, remesh, &t.remesh);
  if (!mesh.ok()) {
    t.stream = mesh.status();
    return t;
  }
  t.base_vertices = mesh->hierarchy.NumVertices(0);
  t.stream = EncodeChoosingLevels(*mesh, options, &t.report, &t.levels);
  return t;
}

// The next base size, `factor` times `from`, or 0 outside the walk's range.
size_t StepFrom(size_t from, double factor, size_t input_vertices) {
  const auto n = static_cast<size_t>(std::llround(static_cast<double>(from) * factor));
  if (n == from || n < kMinWalkBaseVertices || n > input_vertices / kMinInputPerBaseVertex) return 0;
  return n;
}

}  // namespace

EncodeOptions ToBeat(const EncodeOptions& options, const StatusOr<std::vector<uint8_t>>& best,
                     const EncodeReport& best_report) {
  EncodeOptions o = options;
  if (options.target_psnr <= 0 || !best.ok()) return o;
  if (best_report.lambda > 0) o.lambda = best_report.lambda;
  o.outbid_bytes = best->size();
  return o;
}

bool BeatsAtTarget(const EncodeOptions& options, const BaseSizeTry& a, const BaseSizeTry& b) {
  if (!a.stream.ok()) return false;
  if (!b.stream.ok()) return true;
  if (options.target_psnr > 0) return a.report.total_bytes < b.report.total_bytes;
  return a.report.psnr_db > b.report.psnr_db;
}

bool BaseWalkApplies(const EncodeOptions& options) {
  const bool targeted = options.target_psnr > 0 || options.target_bpv > 0;
  return targeted && options.original != nullptr && options.original->positions.size() <= kBaseWalkMaxInputVertices;
}

BaseSizeTry WalkBaseSizes(const Mesh& input, const RemeshOptions& remesh, const EncodeOptions& options,
                          BaseSizeTry first, std::vector<size_t>* tried) {
  const size_t start = first.base_vertices;
  const size_t input_vertices = input.positions.size();
  BaseSizeTry best = std::move(first);
  // A stream that missed its target is short of detail: only a finer base can help.
  const bool reached = best.stream.ok();
  for (const double factor : {kBaseStepFactor, 1.0 / kBaseStepFactor}) {
    if (factor < 1.0 && !reached) break;
    size_t n = start;
    bool moved = false;
    for (int step = 0; step < kMaxBaseSteps; ++step) {
      n = StepFrom(n, factor, input_vertices);
      if (n == 0) break;
      if (tried) tried->push_back(n);
      BaseSizeTry t = EncodeAtBaseSize(input, remesh, ToBeat(options, best.stream, best.report), n);
      if (!BeatsAtTarget(options, t, best)) break;
      best = std::move(t);
      moved = true;
    }
    if (moved) break;  // the other way leads from a worse base
  }
  return best;
}

}  // namespace eqmesh

// Modified butterfly prediction and local frames for one refinement j -> j+1.
//
// Contract shared by the remesher (which pierces along these normals from these
// points), the wavelet transform and the decoder: everything here depends only on
// the level-j connectivity and level-j positions, so a decoder can recompute it.
//
// Papers: Dyn, Levin, Gregory 1990 (8-point butterfly); Zorin, Schröder, Sweldens
// 1996 (modified butterfly: extraordinary-vertex and boundary rules).
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/semi_regular.h"
#include "wavelet/level_adjacency.h"

namespace eqmesh {

// Sparse linear stencils in CSR form: odd vertex k of level j is predicted as
// sum_{i in [offsets[k], offsets[k+1])} weights[i] * position[indices[i]],
// indices referring to level-j vertices.
struct StencilTable {
  std::vector<uint32_t> offsets;
  std::vector<uint32_t> indices;
  std::vector<double> weights;
  size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

// Accumulates one stencil, merging repeated indices in first-seen order; reused
// across edges so the per-edge cost is allocation-free.
class StencilBuilder {
 public:
  void Clear() { terms_.clear(); }
  void Add(uint32_t v, double w);
  // Appends the terms, exact zeros dropped, as one row of `table`.
  void AppendTo(StencilTable* table) const;
  // The row AppendTo would write, applied to `values` as ApplyStencils does.
  Vec3 Apply(const std::vector<Vec3>& values) const;

 private:
  std::vector<std::pair<uint32_t, double>> terms_;
};

// Orthonormal frame at an odd vertex's predicted point.
struct LocalFrame {
  Vec3 normal = Vec3::UnitZ();
  Vec3 tangent = Vec3::UnitX();    // along the parent edge, projected to the tangent plane
  Vec3 bitangent = Vec3::UnitY();  // normal x tangent
};

// Neighbour weights s_0..s_{k-1} of Zorin et al.'s rule at an interior vertex of
// valence k >= 3 (the vertex itself gets 3/4; s_0 belongs to the other endpoint of
// the edge, s_i to the i-th ring neighbour after it in either rotational
// direction). Empty for k < 3. Exposed for tests and the format spec.
std::vector<double> ButterflyExtraordinaryWeights(uint32_t k);

// The stencils of refinement j -> j+1 one at a time, for callers that apply each
// once (a decoder): no table is stored, which at the finest level saves more
// memory than the level's positions take. Stencil(k) is row k of
// BuildButterflyStencils, and its Apply gives what ApplyStencils gives. Holds a
// reference to `hierarchy`; not thread-safe (one builder is reused).
class CreaseEdges;

class ButterflyPredictor {
 public:
  ButterflyPredictor(const SemiRegularHierarchy& hierarchy, int j);
  ~ButterflyPredictor();
  // Its crease edges refer to its adjacency: it stays where it was built.
  ButterflyPredictor(const ButterflyPredictor&) = delete;
  ButterflyPredictor& operator=(const ButterflyPredictor&) = delete;
  const StencilBuilder& Stencil(uint32_t k) const;
  const SemiRegularHierarchy& hierarchy() const { return hierarchy_; }
  int level() const { return j_; }
  const LevelAdjacency& adjacency() const { return adjacency_; }

 private:
  const SemiRegularHierarchy& hierarchy_;
  int j_;
  LevelAdjacency adjacency_;
  std::unique_ptr<const CreaseEdges> creases_;  // of level j (crease_edges.h)
  mutable StencilBuilder builder_;
};

// Modified butterfly stencils for all odd vertices of refinement j -> j+1,
// including extraordinary (valence != 6), boundary and crease rules (the
// hierarchy's tagged edges). Connectivity only.
StencilTable BuildButterflyStencils(const SemiRegularHierarchy& hierarchy, int j);

// out[k] = stencil k applied to `positions` (positions.size() >= NumVertices(j)).
void ApplyStencils(const StencilTable& stencils, const std::vector<Vec3>& positions,
                   std::vector<Vec3>* out);

// Frame of each odd vertex of refinement j -> j+1 from level-j positions only
// (positions.size() >= NumVertices(j); extra entries are ignored). Normative rules,
// restated exactly in butterfly.cpp's header:
// normal = normalize(stencil applied to the area-weighted unit vertex normals of
// level j), falling back to the two faces of the edge, then to +Z;
// tangent = parent edge direction (b - a) projected onto the tangent plane,
// falling back to the world axis least aligned with the normal;
// bitangent = normal x tangent.
std::vector<LocalFrame> ComputeOddFrames(const SemiRegularHierarchy& hierarchy, int j,
                                         const StencilTable& stencils,
                                         const std::vector<Vec3>& positions);

// The same frames one odd vertex at a time, for a decoder that needs them only
// where a detail is non-zero. Frame(k) equals ComputeOddFrames(...)[k] exactly.
// Holds references to its arguments, which must outlive it; not thread-safe
// (the fallback's adjacency is built on first use).
class OddFrames {
 public:
  OddFrames(const SemiRegularHierarchy& hierarchy, int j, const StencilTable& stencils,
            const std::vector<Vec3>& positions);
  OddFrames(const ButterflyPredictor& predictor, const std::vector<Vec3>& positions);
  ~OddFrames();
  LocalFrame Frame(uint32_t k) const;

 private:
  const LevelAdjacency& Adjacency() const;
  Vec3 StencilNormal(uint32_t k) const;

  const SemiRegularHierarchy& hierarchy_;
  int j_;
  const StencilTable* stencils_ = nullptr;        // one of these two is set
  const ButterflyPredictor* predictor_ = nullptr;
  const std::vector<Vec3>& positions_;
  std::vector<Vec3> vertex_normals_;
  mutable std::unique_ptr<LevelAdjacency> adjacency_;
};

}  // namespace eqmesh

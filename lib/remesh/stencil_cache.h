// Butterfly stencils of a hierarchy's levels, built on first use and kept.
//
// They depend on connectivity only, so every untangling trial, the non-normal
// marking and the patch refills can share them (igea, 1.6M vertices: the
// untangling takes 0.70 s sharing them, 1.84 s building them per use).
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "mesh/semi_regular.h"
#include "wavelet/butterfly.h"

namespace eqmesh {

class StencilCache {
 public:
  // `built[j]`, when given, must be BuildButterflyStencils(hierarchy, j): the
  // refinement's own tables, borrowed (they must outlive the cache) so the
  // untangling of every level does not build or copy them again.
  explicit StencilCache(const SemiRegularHierarchy& hierarchy, const std::vector<StencilTable>& built = {})
      : hierarchy_(hierarchy), tables_(static_cast<size_t>(hierarchy.levels())) {
    const size_t borrowed = std::min(built.size(), tables_.size());
    for (size_t j = 0; j < borrowed; ++j) borrowed_.push_back(&built[j]);
  }

  // Stencils of refinement j -> j+1 (BuildButterflyStencils).
  const StencilTable& Level(int j) {
    const auto level = static_cast<size_t>(j);
    if (level < borrowed_.size()) return *borrowed_[level];
    std::optional<StencilTable>& t = tables_[level];
    if (!t) t = BuildButterflyStencils(hierarchy_, j);
    return *t;
  }

 private:
  const SemiRegularHierarchy& hierarchy_;
  std::vector<const StencilTable*> borrowed_;
  std::vector<std::optional<StencilTable>> tables_;
};

}  // namespace eqmesh

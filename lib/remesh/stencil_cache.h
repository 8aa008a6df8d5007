// Butterfly stencils of a hierarchy's levels, built on first use and kept.
//
// They depend on connectivity only, so every untangling trial, the non-normal
// marking and the patch refills can share them (igea, 1.6M vertices: the
// untangling takes 0.70 s sharing them, 1.84 s building them per use).
#pragma once

#include <optional>
#include <vector>

#include "mesh/semi_regular.h"
#include "wavelet/butterfly.h"

namespace eqmesh {

class StencilCache {
 public:
  // `built[j]`, when given, must be BuildButterflyStencils(hierarchy, j): the
  // refinement's own tables, so the untangling does not build them again.
  explicit StencilCache(const SemiRegularHierarchy& hierarchy, std::vector<StencilTable> built = {})
      : hierarchy_(hierarchy), tables_(static_cast<size_t>(hierarchy.levels())) {
    for (size_t j = 0; j < built.size() && j < tables_.size(); ++j) tables_[j] = std::move(built[j]);
  }

  // Stencils of refinement j -> j+1 (BuildButterflyStencils).
  const StencilTable& Level(int j) {
    std::optional<StencilTable>& t = tables_[static_cast<size_t>(j)];
    if (!t) t = BuildButterflyStencils(hierarchy_, j);
    return *t;
  }

 private:
  const SemiRegularHierarchy& hierarchy_;
  std::vector<std::optional<StencilTable>> tables_;
};

}  // namespace eqmesh

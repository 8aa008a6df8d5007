// Checks of a remesh against its input, for `eqmesh remesh --json` and the
// bench: folded faces (normal opposed to the input's at the closest point of
// the face centroid) and degenerate faces (zero area at the input's scale).
#pragma once

#include <cstddef>

#include "core/status.h"
#include "mesh/mesh.h"

namespace eqmesh {

struct FoldReport {
  size_t flipped_faces = 0;
  size_t degenerate_faces = 0;
};

StatusOr<FoldReport> CountFoldsAgainstInput(const Mesh& remesh, const Mesh& input);

}  // namespace eqmesh

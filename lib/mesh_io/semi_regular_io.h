// Lossless file format for a remeshed SemiRegularMesh (".srm"), so a benchmark can
// remesh once and encode many times, and a user can inspect the remesher's output
// exactly (positions as doubles, vertex kinds, components kept exactly).
//
// Layout (little endian): "EQSR" u8 version (1; 2 with crease edges) u8 levels u16 reserved(0)
// u32 base_vertices u32 base_faces, base faces (3 x u32 each),
// u32 vertex_count (must equal NumVertices(levels)), positions (3 x f64 each),
// u8 has_kinds, kinds (u8 each, when has_kinds), [version 2: u32 crease_edges,
// crease base edges (2 x u32 each)], u32 kept_vertices u32 kept_faces,
// kept positions (3 x f64), kept faces (3 x u32). Nothing may follow.
#pragma once

#include <string>

#include "core/status.h"
#include "mesh/semi_regular.h"

namespace eqmesh {

Status WriteSemiRegular(const SemiRegularMesh& mesh, const std::string& path);
StatusOr<SemiRegularMesh> ReadSemiRegular(const std::string& path);

}  // namespace eqmesh

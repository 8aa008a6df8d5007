// `eqmesh info STREAM.eqm`: what a stream holds, from its header and its base
// chunk alone (no level is decoded): format version and flags, coding
// parameters, every chunk's byte range, and the vertex and face count of each
// level a progressive loader can stop at.
#pragma once

#include <string>

namespace eqmesh::cli {

// Whether `path` names an eqmesh stream: the .eqm extension or the stream magic.
bool LooksLikeStream(const std::string& path);

// Prints the report (a table, or one JSON object); returns the exit code.
int PrintStreamInfo(const std::string& path, bool json);

}  // namespace eqmesh::cli

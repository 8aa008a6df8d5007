// One-line progress display for long commands (remesh, encode).
#pragma once

#include "core/progress.h"

namespace eqmesh::cli {

// Draws "stage  42%" on one terminal line of stderr; nullptr (no display) when
// stderr is not a TTY, so logs and pipes stay clean.
ProgressFn TerminalProgress();

// Clears the progress line (call before printing the result).
void ClearTerminalProgress(const ProgressFn& progress);

}  // namespace eqmesh::cli

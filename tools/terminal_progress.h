// One-line progress display for long commands (remesh, encode).
#pragma once

#include "core/progress.h"

namespace eqmesh::cli {

// Draws "stage  42%" on one terminal line of stderr; nullptr (no display) when
// stderr is not a TTY, so logs and pipes stay clean, or when `quiet` (--json:
// the caller's output is for a program).
ProgressFn TerminalProgress(bool quiet = false);

// Clears the progress line (call before printing the result).
void ClearTerminalProgress(const ProgressFn& progress);

}  // namespace eqmesh::cli

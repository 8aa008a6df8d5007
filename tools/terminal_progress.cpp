#include "tools/terminal_progress.h"

#include <cstdio>
#include <string>
#include <unistd.h>

namespace eqmesh::cli {

ProgressFn TerminalProgress(bool quiet) {
  if (quiet || !isatty(fileno(stderr))) return nullptr;
  return [last = std::string(), last_pct = -1](const std::string& stage, double fraction) mutable {
    const int pct = static_cast<int>(fraction * 100.0);
    if (stage == last && pct == last_pct) return;
    last = stage;
    last_pct = pct;
    std::fprintf(stderr, "\r\033[K%s %3d%%", stage.c_str(), pct);
    std::fflush(stderr);
  };
}

void ClearTerminalProgress(const ProgressFn& progress) {
  if (progress) std::fprintf(stderr, "\r\033[K");
}

}  // namespace eqmesh::cli

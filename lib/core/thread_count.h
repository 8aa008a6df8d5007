// The worker-thread budget of every parallel pass (remesher loops, surface
// distance sampling). Results never depend on it, only speed: passes split work
// into fixed chunks or blocks and combine them in a fixed order, and the
// determinism tests compare outputs at 1, 2 and 4 threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <thread>

namespace eqmesh {

namespace detail {
inline std::atomic<int>& ThreadLimitOverride() {
  static std::atomic<int> limit{0};
  return limit;
}
}  // namespace detail

// Caps the threads later passes use; n <= 0 restores the default.
inline void SetWorkerThreadLimit(int n) { detail::ThreadLimitOverride().store(n > 0 ? n : 0); }

// The cap set above, else the EQMESH_THREADS environment variable, else the
// hardware's thread count (at most 256).
inline int WorkerThreadLimit() {
  if (const int set = detail::ThreadLimitOverride().load(); set > 0) return set;
  if (const char* env = std::getenv("EQMESH_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return std::min(n, 256);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(std::min(hw, 256u)) : 1;
}

}  // namespace eqmesh

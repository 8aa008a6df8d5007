// Minimal fork-join loop for the remesher's embarrassingly parallel passes
// (piercing rays, parameter relocation). Work is split into contiguous chunks.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace eqmesh {

// Calls fn(begin, end, worker) on disjoint chunks covering [0, n).
template <typename Fn>
void ParallelFor(size_t n, const Fn& fn) {
  const size_t hw = std::max<size_t>(1, std::thread::hardware_concurrency());
  const size_t workers = std::min<size_t>({hw, 8, std::max<size_t>(1, n / 256)});
  if (workers <= 1) {
    fn(size_t{0}, n, size_t{0});
    return;
  }
  std::vector<std::thread> threads;
  const size_t chunk = (n + workers - 1) / workers;
  for (size_t w = 0; w < workers; ++w) {
    const size_t begin = std::min(n, w * chunk), end = std::min(n, begin + chunk);
    threads.emplace_back([&fn, begin, end, w] { fn(begin, end, w); });
  }
  for (std::thread& t : threads) t.join();
}

}  // namespace eqmesh

// Minimal fork-join loop for the remesher's embarrassingly parallel passes
// (piercing rays, parameter relocation). Work is split into contiguous chunks.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

#include "core/thread_count.h"

namespace eqmesh {

// Calls fn(begin, end, worker) on disjoint chunks covering [0, n); a worker
// gets at least `min_items` items (too little work is not worth a thread).
template <typename Fn>
void ParallelFor(size_t n, const Fn& fn, size_t min_items = 256) {
  const size_t hw = static_cast<size_t>(WorkerThreadLimit());
  const size_t workers = std::min<size_t>({hw, 8, std::max<size_t>(1, n / std::max<size_t>(1, min_items))});
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

// Sum of fn(begin, end) over fixed chunks of [0, n), added in chunk order:
// floating-point addition is not associative, and a sum that depended on how
// many threads ran (or which finished first) would make the remesher's choices,
// and so its output, vary between machines.
template <typename T, typename Fn>
T ParallelSum(size_t n, const T& zero, const Fn& fn) {
  constexpr size_t kChunk = 2048;
  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<T> partial(chunks, zero);
  ParallelFor(
      chunks,
      [&](size_t begin, size_t end, size_t) {
        for (size_t c = begin; c < end; ++c) partial[c] = fn(c * kChunk, std::min(n, (c + 1) * kChunk));
      },
      1);
  T total = zero;
  for (const T& p : partial) total += p;
  return total;
}

}  // namespace eqmesh

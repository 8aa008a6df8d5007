// ForEachBlock: a dynamic (atomic counter) block schedule; see parallel_blocks.h.
#include "core/parallel_blocks.h"

#include "core/thread_count.h"

#include <algorithm>
#include <atomic>
#include <system_error>
#include <thread>
#include <vector>

namespace eqmesh {

int ResolveThreadCount(int threads) {
  return threads > 0 ? threads : WorkerThreadLimit();
}

void ForEachBlock(uint64_t num_blocks, int threads, const std::function<void(uint64_t)>& fn) {
  std::atomic<uint64_t> next{0};
  auto worker = [&]() {
    for (uint64_t b = next.fetch_add(1); b < num_blocks; b = next.fetch_add(1)) fn(b);
  };
  const uint64_t wanted = std::min<uint64_t>(static_cast<uint64_t>(ResolveThreadCount(threads)), num_blocks);
  std::vector<std::thread> pool;
  for (uint64_t t = 1; t < wanted; ++t) {
    try {
      pool.emplace_back(worker);
    } catch (const std::system_error&) {
      break;  // out of threads: the others (and this one) finish the work
    }
  }
  worker();
  for (std::thread& th : pool) th.join();
}

}  // namespace eqmesh

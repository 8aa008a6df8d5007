// ForEachBlock: run fn(block) for block = 0 .. num_blocks-1 on a few threads.
// Callers write each block's result into its own slot and reduce the slots in
// block order afterwards, which makes the result independent of the thread
// count and of scheduling (the reason the meter is byte-reproducible).
#pragma once

#include <cstdint>
#include <functional>

namespace eqmesh {

// threads <= 0 means std::thread::hardware_concurrency(). If threads cannot
// be started the remaining blocks run on the calling thread (never throws).
void ForEachBlock(uint64_t num_blocks, int threads, const std::function<void(uint64_t)>& fn);

// The thread count ForEachBlock would use for `threads` (>= 1).
int ResolveThreadCount(int threads);

}  // namespace eqmesh

#include "remesh/spin_team.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace eqmesh {
namespace {

// Waiting helpers spin this many rounds, then yield as many, then sleep: about
// a millisecond of spinning covers the gap between two collapses many times
// over, and a caller that stops for longer does not keep a core busy.
constexpr int kSpinRounds = 1 << 14;
constexpr int kYieldRounds = 1 << 10;

void CpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

}  // namespace

SpinTeam::SpinTeam(int workers) {
  for (int w = 1; w < workers; ++w) helpers_.emplace_back([this, w] { HelperLoop(w); });
}

SpinTeam::~SpinTeam() {
  stop_.store(true);
  batch_.fetch_add(1);
  {
    std::lock_guard<std::mutex> guard(sleep_lock_);
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

void SpinTeam::Run(size_t n, const std::function<void(size_t, int)>& fn) {
  if (helpers_.empty() || n < 2) {
    for (size_t i = 0; i < n; ++i) fn(i, 0);
    return;
  }
  n_ = n;
  fn_ = &fn;
  next_.store(0);
  finished_.store(0);
  // seq_cst with the helpers' sleepers_ increment: either they see the new
  // batch before sleeping or this sees them asleep and wakes them.
  batch_.fetch_add(1);
  if (sleepers_.load() > 0) {
    { std::lock_guard<std::mutex> guard(sleep_lock_); }
    wake_.notify_all();
  }
  Work(0);
  // Every helper must have left the batch before n_ and fn_ may change.
  while (finished_.load(std::memory_order_acquire) != helpers_.size()) CpuRelax();
}

void SpinTeam::Work(int worker) {
  for (size_t i = next_.fetch_add(1); i < n_; i = next_.fetch_add(1)) (*fn_)(i, worker);
}

bool SpinTeam::WaitForBatch(uint64_t seen) {
  for (int round = 0; round < kSpinRounds; ++round) {
    if (batch_.load(std::memory_order_acquire) != seen) return !stop_.load();
    CpuRelax();
  }
  for (int round = 0; round < kYieldRounds; ++round) {
    if (batch_.load(std::memory_order_acquire) != seen) return !stop_.load();
    std::this_thread::yield();
  }
  std::unique_lock<std::mutex> guard(sleep_lock_);
  sleepers_.fetch_add(1);
  wake_.wait(guard, [&] { return batch_.load() != seen; });
  sleepers_.fetch_sub(1);
  return !stop_.load();
}

void SpinTeam::HelperLoop(int worker) {
  uint64_t seen = 0;
  while (WaitForBatch(seen)) {
    seen = batch_.load(std::memory_order_acquire);
    Work(worker);
    finished_.fetch_add(1, std::memory_order_release);
  }
}

}  // namespace eqmesh

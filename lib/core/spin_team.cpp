#include "core/spin_team.h"

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

SpinTeam::SpinTeam(int workers) : tickets_(static_cast<size_t>(workers > 1 ? workers : 1)) {
  for (auto& t : tickets_) t.store(1);  // batch 0 is over for everyone
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
  // seq_cst with the helpers' sleepers_ increment: either they see the new
  // batch before sleeping or this sees them asleep and wakes them.
  const uint64_t batch = batch_.fetch_add(1) + 1;
  if (sleepers_.load() > 0) {
    { std::lock_guard<std::mutex> guard(sleep_lock_); }
    wake_.notify_all();
  }
  Work(0);
  // Every helper must be out of the batch before n_ and fn_ may change.
  for (int w = 1; w <= static_cast<int>(helpers_.size()); ++w) ShutOutOrAwait(w, batch);
}

bool SpinTeam::Enter(int worker, uint64_t batch) {
  std::atomic<uint64_t>& ticket = tickets_[static_cast<size_t>(worker)];
  uint64_t t = ticket.load(std::memory_order_acquire);
  // A ticket of batch or later: this batch is already over for this helper.
  return t < 2 * batch && ticket.compare_exchange_strong(t, 2 * batch, std::memory_order_acq_rel);
}

void SpinTeam::ShutOutOrAwait(int worker, uint64_t batch) {
  std::atomic<uint64_t>& ticket = tickets_[static_cast<size_t>(worker)];
  uint64_t t = ticket.load(std::memory_order_acquire);
  if (t < 2 * batch && ticket.compare_exchange_strong(t, 2 * batch + 1, std::memory_order_acq_rel)) return;
  // It entered first: its indices are claimed, so it is running fn and ends soon
  // unless descheduled, when yielding lets it finish sooner.
  for (int round = 0; ticket.load(std::memory_order_acquire) != 2 * batch + 1; ++round) {
    if (round < kSpinRounds) {
      CpuRelax();
    } else {
      std::this_thread::yield();
    }
  }
}

void SpinTeam::Work(int worker) {
  for (size_t i = next_.fetch_add(1); i < n_; i = next_.fetch_add(1)) (*fn_)(i, worker);
}

// Stop is part of the wake-up condition, not only of the answer: a helper that
// read `seen` after the destructor's batch_ increment (it returned from its last
// wait just before stop_ was set) would otherwise wait for a batch that never
// comes, and the destructor's join would hang (tests/core: DestroyedRightAfterABatchNeverHangs).
bool SpinTeam::WaitForBatch(uint64_t seen) {
  const auto ready = [&] { return stop_.load() || batch_.load(std::memory_order_acquire) != seen; };
  for (int round = 0; round < kSpinRounds; ++round) {
    if (ready()) return !stop_.load();
    CpuRelax();
  }
  for (int round = 0; round < kYieldRounds; ++round) {
    if (ready()) return !stop_.load();
    std::this_thread::yield();
  }
  std::unique_lock<std::mutex> guard(sleep_lock_);
  sleepers_.fetch_add(1);
  wake_.wait(guard, ready);
  sleepers_.fetch_sub(1);
  return !stop_.load();
}

void SpinTeam::HelperLoop(int worker) {
  uint64_t seen = 0;
  while (WaitForBatch(seen)) {
    seen = batch_.load(std::memory_order_acquire);
    if (!Enter(worker, seen)) continue;
    Work(worker);
    tickets_[static_cast<size_t>(worker)].store(2 * seen + 1, std::memory_order_release);
  }
}

}  // namespace eqmesh

// A team of threads kept awake for many tiny parallel batches.
//
// ParallelFor starts threads per call, which costs tens of microseconds; the
// base-domain simplification needs a batch after every one of its ~n collapses
// (the costs of the ~6 vertices around it, a few microseconds each), so its
// helpers must already be running and waiting. They spin between batches, then
// yield, then sleep on a condition variable once a batch has not come for a
// while, so an idle team costs nothing when the caller stops for long.
//
// Results never depend on the team: a batch calls fn(i, worker) once for every
// i, the caller combines them in index order, and Run returns only when every
// call has finished.
//
// A helper takes part in a batch only if it enters it before the caller has
// finished the batch's indices itself: the caller then shuts it out (one
// compare-and-swap on the helper's ticket decides who came first) instead of
// waiting for it, so a helper descheduled on a loaded machine cannot hold up every
// batch for a time slice (measured: bench/log/2026-12-05-developers-history.md).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace eqmesh {

class SpinTeam {
 public:
  // `workers` threads in all, the caller included; 1 runs batches inline.
  explicit SpinTeam(int workers);
  ~SpinTeam();
  SpinTeam(const SpinTeam&) = delete;
  SpinTeam& operator=(const SpinTeam&) = delete;

  int workers() const { return static_cast<int>(helpers_.size()) + 1; }
  // fn(i, worker) for i in [0, n), worker in [0, workers()).
  void Run(size_t n, const std::function<void(size_t, int)>& fn);

 private:
  void HelperLoop(int worker);
  void Work(int worker);
  bool WaitForBatch(uint64_t seen);

  bool Enter(int worker, uint64_t batch);
  void ShutOutOrAwait(int worker, uint64_t batch);

  std::vector<std::thread> helpers_;
  std::atomic<uint64_t> batch_{0};     // generation of the current batch
  std::atomic<size_t> next_{0};        // next index to claim
  // Per helper: 2g while it works on batch g, 2g + 1 once batch g is over for it
  // (it finished, or the caller shut it out).
  std::vector<std::atomic<uint64_t>> tickets_;
  std::atomic<bool> stop_{false};
  size_t n_ = 0;
  const std::function<void(size_t, int)>* fn_ = nullptr;
  std::mutex sleep_lock_;
  std::condition_variable wake_;
  std::atomic<int> sleepers_{0};
};

}  // namespace eqmesh

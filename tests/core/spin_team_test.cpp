#include "core/spin_team.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace eqmesh {
namespace {

// Every batch calls each index exactly once, from a worker in range, and
// returns only after all of them finished (the counts are read right after).
void ExpectEachIndexOnce(SpinTeam* team, size_t n) {
  std::vector<std::atomic<int>> calls(n);
  std::atomic<bool> bad_worker{false};
  team->Run(n, [&](size_t i, int worker) {
    if (worker < 0 || worker >= team->workers()) bad_worker = true;
    calls[i].fetch_add(1);
  });
  EXPECT_FALSE(bad_worker);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(calls[i].load(), 1) << "index " << i << " of " << n;
}

// One yielding busy thread per core while it lives: the team's helpers get
// descheduled at arbitrary points.
class BusyThreads {
 public:
  BusyThreads() {
    const unsigned cores = std::max(2u, std::thread::hardware_concurrency());
    for (unsigned k = 0; k < cores; ++k) {
      threads_.emplace_back([this] {
        while (!stop_.load(std::memory_order_relaxed)) std::this_thread::yield();
      });
    }
  }
  ~BusyThreads() {
    stop_ = true;
    for (std::thread& t : threads_) t.join();
  }
  BusyThreads(const BusyThreads&) = delete;
  BusyThreads& operator=(const BusyThreads&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

TEST(SpinTeam, ManyTinyBatchesCallEveryIndexOnce) {
  SpinTeam team(2);
  EXPECT_EQ(team.workers(), 2);
  for (int batch = 0; batch < 20000; ++batch) ExpectEachIndexOnce(&team, static_cast<size_t>(batch % 9));
}

TEST(SpinTeam, WakesHelpersThatFellAsleep) {
  SpinTeam team(3);
  for (int batch = 0; batch < 5; ++batch) {
    ExpectEachIndexOnce(&team, 64);
    // Longer than the spin and yield phases: the helpers go to sleep.
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
}

// More runnable threads than cores: helpers are often descheduled, so batches
// end without them (shut out) or with them (entered first); either way every
// index runs once, and a helper shut out of one batch joins a later one.
TEST(SpinTeam, OversubscribedBatchesStillCallEveryIndexOnce) {
  const BusyThreads busy;
  SpinTeam team(3);
  for (int batch = 0; batch < 10000; ++batch) ExpectEachIndexOnce(&team, static_cast<size_t>(batch % 13));
}

// A team destroyed right after a batch, while its helpers are still on their way
// back from it: none may miss the stop and wait for a batch that never comes (the
// destructor's join hung once in ctest -j2). Oversubscribed, so that a helper is
// often descheduled between seeing a batch and reading its number.
TEST(SpinTeam, DestroyedRightAfterABatchNeverHangs) {
  const BusyThreads busy;
  for (int round = 0; round < 3000; ++round) {
    SpinTeam team(3);
    ExpectEachIndexOnce(&team, static_cast<size_t>(2 + round % 5));
  }
}

TEST(SpinTeam, OneWorkerRunsInline) {
  SpinTeam team(1);
  EXPECT_EQ(team.workers(), 1);
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  team.Run(10, [&](size_t, int) { elsewhere |= std::this_thread::get_id() != caller; });
  EXPECT_FALSE(elsewhere);
}

}  // namespace
}  // namespace eqmesh

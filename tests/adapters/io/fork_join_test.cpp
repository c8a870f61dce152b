#include "mocaplink/io/fork_join.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

#include <gtest/gtest.h>

#include "mocaplink/io/send_threads.hpp"
#include "scoped_env.hpp"

namespace mocaplink::io {
namespace {

TEST(ForkJoin, PartZeroRunsOnTheCallerAndTheOthersOnDistinctWorkers) {
  ForkJoin pool(3);
  EXPECT_EQ(pool.workers(), 0u);
  std::vector<std::thread::id> ids(3);
  pool.run(3, [&](std::size_t part) { ids[part] = std::this_thread::get_id(); });
  EXPECT_EQ(ids[0], std::this_thread::get_id());
  EXPECT_NE(ids[1], ids[0]);
  EXPECT_NE(ids[2], ids[0]);
  EXPECT_NE(ids[1], ids[2]);
  EXPECT_EQ(pool.workers(), 2u);
}

TEST(ForkJoin, OnePartStartsNoWorker) {
  ForkJoin pool(4);
  std::thread::id id;
  pool.run(1, [&](std::size_t) { id = std::this_thread::get_id(); });
  EXPECT_EQ(id, std::this_thread::get_id());
  EXPECT_EQ(pool.workers(), 0u);
}

TEST(ForkJoin, PartsAreClampedToTheMaximum) {
  ForkJoin pool(2);
  std::atomic<int> calls{0};
  pool.run(8, [&](std::size_t part) {
    EXPECT_LT(part, 2u);
    ++calls;
  });
  EXPECT_EQ(calls.load(), 2);
  pool.run(0, [&](std::size_t part) {
    EXPECT_EQ(part, 0u);
    ++calls;
  });
  EXPECT_EQ(calls.load(), 3);
}

// Every part of every run is called exactly once, and what the parts wrote is visible when run()
// returns — over many runs with a changing number of parts, so a worker started late, one left out
// of a smaller run, or one that sees a run twice would show (plain ints: ThreadSanitizer builds
// see any missing happens-before).
TEST(ForkJoin, EveryPartOnceWithItsWritesVisibleAfterRun) {
  ForkJoin pool(4);
  std::vector<int> count(4, 0);
  std::vector<int> expected(4, 0);
  for (int round = 0; round < 2000; ++round) {
    // Up to 1, 2, 3 and then 4 parts: each worker is started after earlier runs.
    const int most = 1 + round / 500;
    const auto parts = static_cast<std::size_t>(1 + round * 7 % most);
    pool.run(parts, [&](std::size_t part) { ++count[part]; });
    for (std::size_t p = 0; p < parts; ++p) ++expected[p];
    ASSERT_EQ(count, expected) << "round " << round << ", " << parts << " parts";
  }
}

// The parts really run at the same time: part 0 waits until part 1 has started. (A pool that ran
// the parts one after another would never get there; the deadline only keeps a broken pool from
// hanging the test.)
TEST(ForkJoin, PartsRunConcurrently) {
  ForkJoin pool(2);
  std::mutex m;
  std::condition_variable cv;
  bool second_started = false;
  bool first_saw_second = false;
  pool.run(2, [&](std::size_t part) {
    std::unique_lock lock(m);
    if (part == 1) {
      second_started = true;
      cv.notify_all();
    } else {
      first_saw_second =
          cv.wait_for(lock, std::chrono::seconds(30), [&] { return second_started; });
    }
  });
  EXPECT_TRUE(first_saw_second);
}

TEST(ForkJoin, DestroyedWhileWorkersSleep) {
  auto pool = std::make_unique<ForkJoin>(3);
  int sum = 0;
  std::mutex m;
  pool->run(3, [&](std::size_t part) {
    const std::lock_guard lock(m);
    sum += static_cast<int>(part);
  });
  pool.reset();  // joins the two workers
  EXPECT_EQ(sum, 3);
}

TEST(SendThreads, OneThreadPerHundredVehiclesUpToTheMaximum) {
  EXPECT_EQ(send_threads_for(0, 4), 1u);
  EXPECT_EQ(send_threads_for(1, 4), 1u);
  EXPECT_EQ(send_threads_for(kVehiclesPerSendThread, 4), 1u);
  EXPECT_EQ(send_threads_for(kVehiclesPerSendThread + 1, 4), 2u);
  EXPECT_EQ(send_threads_for(3 * kVehiclesPerSendThread, 4), 3u);
  EXPECT_EQ(send_threads_for(1000, 4), 4u);
  EXPECT_EQ(send_threads_for(1000, 2), 2u);
  EXPECT_EQ(send_threads_for(1000, 1), 1u);
  EXPECT_EQ(send_threads_for(1000, 0), 1u);
}

#if defined(__linux__)
/// Restricts the calling thread to the first `n` CPUs of its affinity (as taskset or systemd's
/// CPUAffinity= would, for the process) for the object's lifetime; `ok` is false when it has fewer.
class ScopedAffinity {
 public:
  explicit ScopedAffinity(int n) {
    CPU_ZERO(&saved_);
    if (sched_getaffinity(0, sizeof saved_, &saved_) != 0 || CPU_COUNT(&saved_) < n) return;
    cpu_set_t fewer;
    CPU_ZERO(&fewer);
    int taken = 0;
    for (std::size_t cpu = 0; cpu < CPU_SETSIZE && taken < n; ++cpu) {
      if (CPU_ISSET(cpu, &saved_)) {
        CPU_SET(cpu, &fewer);
        ++taken;
      }
    }
    ok = sched_setaffinity(0, sizeof fewer, &fewer) == 0;
  }
  ~ScopedAffinity() {
    if (ok) sched_setaffinity(0, sizeof saved_, &saved_);
  }
  ScopedAffinity(const ScopedAffinity&) = delete;
  ScopedAffinity& operator=(const ScopedAffinity&) = delete;
  bool ok = false;

 private:
  cpu_set_t saved_;
};
#endif

TEST(SendThreads, MaximumFromTheEnvironment) {
  using testing_support::ScopedEnv;
  std::string warning;
  const ScopedEnv env("MOCAPLINK_SEND_THREADS", "3");
  EXPECT_EQ(max_send_threads(&warning), 3u);
  EXPECT_EQ(warning, "");
}

TEST(SendThreads, AMalformedMaximumIsIgnoredWithAWarning) {
  using testing_support::ScopedEnv;
  std::size_t by_cores = 0;
  {
    const ScopedEnv env("MOCAPLINK_SEND_THREADS", nullptr);
    std::string warning;
    by_cores = max_send_threads(&warning);
    EXPECT_EQ(warning, "");
  }
  for (const char* bad : {"0", "65", "two", "2x", "-1"}) {
    const ScopedEnv env("MOCAPLINK_SEND_THREADS", bad);
    std::string warning;
    EXPECT_EQ(max_send_threads(&warning), by_cores) << bad;
    EXPECT_EQ(warning, std::string("MOCAPLINK_SEND_THREADS=") + bad +
                           " ignored: expected a whole number from 1 to 64");
  }
}

TEST(SendThreads, AsManyAsTheCoresTheProcessMayRunOn) {
  const testing_support::ScopedEnv env("MOCAPLINK_SEND_THREADS", nullptr);
#if defined(__linux__)
  // Its CPU affinity, not the machine's cores: one when restricted to one (taskset -c 0).
  {
    const ScopedAffinity one_core(1);
    if (!one_core.ok) GTEST_SKIP() << "the CPU affinity cannot be set here";
    EXPECT_EQ(max_send_threads(nullptr), 1u);
  }
  const ScopedAffinity two_cores(2);
  if (!two_cores.ok) GTEST_SKIP() << "fewer than two CPUs to run on";
  EXPECT_EQ(max_send_threads(nullptr), 2u);
#else
  const auto cores = std::max(1U, std::thread::hardware_concurrency());
  EXPECT_EQ(max_send_threads(nullptr), std::min<std::size_t>(cores, kMaxSendThreads));
#endif
}

}  // namespace
}  // namespace mocaplink::io

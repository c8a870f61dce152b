// ForkJoin: runs one task on several threads at once and returns when every part is done — how the
// daemon spreads a frame's sends over worker threads when one core is not enough (issue 15;
// docs/daemon.md "Threads").
//
//   io::ForkJoin pool(4);                       // up to 4 parts: the caller's thread + 3 workers
//   pool.run(parts, [&](std::size_t part) {     // part 0 runs on the caller's thread, the others
//     for (auto v = part; v < n; v += parts) send(v);   // on workers, all at once
//   });                                         // returns when every part has returned
//
// The caller is parked inside run() until the last part has returned, and run() returning
// happens-after everything the parts did (and every part starts after everything the caller did
// before run()): objects the caller's thread owns may be used by the parts without locks as long
// as no two parts touch the same one. That is what lets an event loop's thread lend its UDP links
// to workers for one frame (io::Link::sends_in_place).
//
// Workers are started on first use and sleep between runs (no spinning); the destructor stops and
// joins them. run() does not allocate. Not reentrant: call run() from one thread at a time, and
// not from inside a part. A part must not throw (the process terminates).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace mocaplink::io {

class ForkJoin {
 public:
  /// At most `max_parts` parts per run (≥ 1; 0 is treated as 1), so at most max_parts − 1 workers.
  explicit ForkJoin(std::size_t max_parts);
  ~ForkJoin();
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  [[nodiscard]] std::size_t max_parts() const noexcept { return max_parts_; }
  /// Workers started so far (they are started when a run first needs them).
  [[nodiscard]] std::size_t workers() const noexcept { return workers_.size(); }

  /// Calls task(part) for every part in [0, parts): part 0 on this thread, the others on workers,
  /// concurrently; returns when all have returned. `parts` is clamped to [1, max_parts()].
  template <typename Task>
  void run(std::size_t parts, Task&& task) {
    using T = std::remove_reference_t<Task>;
    run_parts(parts, &task, [](void* t, std::size_t part) { (*static_cast<T*>(t))(part); });
  }

 private:
  using Trampoline = void (*)(void*, std::size_t);
  void run_parts(std::size_t parts, void* task, Trampoline call);
  void work(std::size_t part, std::uint64_t seen);

  const std::size_t max_parts_;
  std::vector<std::thread> workers_;  // workers_[i] runs part i + 1; only the caller changes it
  std::mutex mutex_;
  std::condition_variable start_;  // workers wait here for a new generation (or stop)
  std::condition_variable done_;   // the caller waits here for remaining_ == 0
  std::uint64_t generation_ = 0;   // guarded by mutex_: one per run
  std::size_t parts_ = 0;          // guarded by mutex_: parts of the current run
  std::size_t remaining_ = 0;      // guarded by mutex_: worker parts not finished
  void* task_ = nullptr;           // guarded by mutex_
  Trampoline call_ = nullptr;      // guarded by mutex_
  bool stopping_ = false;          // guarded by mutex_
};

}  // namespace mocaplink::io

// The worker thread of a source that makes frames on a clock (sim, replay): it waits for each
// frame's due time and must wake at once when told to stop, so that stop() never sleeps until the
// next frame. One implementation of "a thread with an interruptible wait" for every such source.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace mocaplink::sources {

/// Thread-safety: start/stop from one controlling thread; wait_until from the worker thread.
class SourceThread {
 public:
  SourceThread() = default;
  ~SourceThread() { stop(); }
  SourceThread(const SourceThread&) = delete;
  SourceThread& operator=(const SourceThread&) = delete;

  /// Runs `body` on a new thread. Call once.
  void start(std::function<void()> body);
  /// Wakes a waiting wait_until and joins the thread. Idempotent.
  void stop();
  /// Sleeps until `deadline` or until stop(); true if stopping (the body should return).
  template <typename Clock, typename Duration>
  [[nodiscard]] bool wait_until(std::chrono::time_point<Clock, Duration> deadline) {
    std::unique_lock lock(mutex_);
    return wake_.wait_until(lock, deadline, [this] { return stopping_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  // guarded by mutex_
  std::thread thread_;
};

}  // namespace mocaplink::sources

// The thread of a network source's client: its Session (sockets, timers, an io_context) is made
// at start() and runs on its own thread until stop() asks it to stop and joins; and the source's
// most recent error, readable from any thread. One implementation for every client that works
// this way (natnet; the same shape as vicon's), with its state reports and reconnection back-off.
#pragma once

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

/// Session needs run() (blocks until stopped) and stop() (thread-safe, makes run() return).
/// Thread-safety: start/stop from one controlling thread.
template <typename Session>
class SessionThread {
 public:
  SessionThread() = default;
  ~SessionThread() { stop(); }
  SessionThread(const SessionThread&) = delete;
  SessionThread& operator=(const SessionThread&) = delete;

  /// Makes the Session from `args` and runs it on a new thread; later calls do nothing.
  template <typename... Args>
  void start(Args&&... args) {
    if (started_) return;
    started_ = true;
    session_ = std::make_unique<Session>(std::forward<Args>(args)...);
    thread_ = std::thread([s = session_.get()] { s->run(); });
  }

  /// Stops the session, joins its thread and destroys it. Idempotent.
  void stop() {
    if (!session_) return;
    session_->stop();
    if (thread_.joinable()) thread_.join();
    session_.reset();
  }

 private:
  std::unique_ptr<Session> session_;
  std::thread thread_;
  bool started_ = false;
};

/// A text set on one thread and read on any other.
class LastError {
 public:
  [[nodiscard]] std::string get() const {
    std::lock_guard lock(mutex_);
    return text_;
  }
  void set(std::string text) {
    std::lock_guard lock(mutex_);
    text_ = std::move(text);
  }

 private:
  mutable std::mutex mutex_;
  std::string text_;  // guarded by mutex_
};

/// A connection state as the StateSink hears it: each change once; every `disconnected` (each
/// carries its own reason). Session thread only.
class StateReporter {
 public:
  explicit StateReporter(StateSink sink) : sink_(std::move(sink)) {}
  void set(SourceState s, const std::string& detail) {
    if (s == state_ && s != SourceState::disconnected) return;
    state_ = s;
    if (sink_) sink_(s, detail);
  }

 private:
  StateSink sink_;
  SourceState state_ = SourceState::disconnected;
};

/// Reconnection delays: `initial`, doubling up to `max`, back to `initial` after a success.
class Backoff {
 public:
  Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds max)
      : initial_(initial), max_(max), next_(initial) {}
  /// The delay before the next attempt; the one after is twice as long (capped).
  std::chrono::milliseconds next() {
    const auto now = next_;
    next_ = std::min(next_ * 2, max_);
    return now;
  }
  void reset() { next_ = initial_; }

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds max_;
  std::chrono::milliseconds next_;
};

}  // namespace mocaplink::sources

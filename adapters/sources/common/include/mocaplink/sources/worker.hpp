// The thread of a source or emulator whose work is an event loop (Asio): a Worker owns the loop's
// object — anything with run() (returns when stopped) and stop() (thread-safe, wakes run()) — and
// the thread that runs it, so every such class starts and joins it the same way.
#pragma once

#include <memory>
#include <thread>
#include <utility>

namespace mocaplink::sources {

template <typename Loop>
class Worker {
 public:
  Worker() = default;
  ~Worker() { stop(); }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  /// Takes `loop` and runs `loop->run()` on a new thread. Call once (or after stop()).
  void start(std::unique_ptr<Loop> loop) {
    loop_ = std::move(loop);
    thread_ = std::thread([l = loop_.get()] { l->run(); });
  }
  /// Stops the loop, joins the thread and destroys the loop. Idempotent.
  void stop() {
    if (!loop_) return;
    loop_->stop();
    if (thread_.joinable()) thread_.join();
    loop_.reset();
  }
  [[nodiscard]] bool running() const { return loop_ != nullptr; }
  /// The loop (null when not running); its thread-safe members only.
  [[nodiscard]] Loop* get() const { return loop_.get(); }

 private:
  std::unique_ptr<Loop> loop_;
  std::thread thread_;
};

}  // namespace mocaplink::sources

// The thread of a socket source or emulator: an object that owns an Asio loop (`run()` until its
// `stop()`), made, then run on its own thread, then stopped and joined. One implementation for
// every network client and server (vicon, natnet, qtm, vrpn, vicon-udp) instead of each repeating
// the start/stop/join dance; and the "last error" text such a source shows, set on its thread and
// read from any.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/source.hpp"  // LastError

namespace mocaplink::sources {

/// Thread-safety: make/run/stop/reset from one controlling thread. `Loop` needs `stop()`, callable
/// from that thread while run() works on the other.
template <typename Loop>
class LoopThread {
 public:
  LoopThread() = default;
  ~LoopThread() { stop(); }
  LoopThread(const LoopThread&) = delete;
  LoopThread& operator=(const LoopThread&) = delete;

  /// Makes the loop object (not yet running); replaces one that never ran.
  template <typename... Args>
  Loop& make(Args&&... args) {
    loop_ = std::make_unique<Loop>(std::forward<Args>(args)...);
    return *loop_;
  }
  /// Runs `body(loop)` on a new thread (once per make()).
  template <typename Body>
  void run(Body body) {
    thread_ = std::thread([this, b = std::move(body)]() mutable { b(*loop_); });
  }
  /// make(args…), then `loop.run()` on the thread: the first time only (a Source's start()).
  template <typename... Args>
  void start_once(Args&&... args) {
    if (started_) return;
    started_ = true;
    make(std::forward<Args>(args)...);
    run([](Loop& loop) { loop.run(); });
  }
  /// Takes a loop made (and perhaps already bound) elsewhere and runs `loop->run()` on a new
  /// thread. Call when not running.
  void start(std::unique_ptr<Loop> loop) {
    loop_ = std::move(loop);
    run([](Loop& l) { l.run(); });
  }
  /// Stops the loop, joins the thread and destroys the loop. Idempotent.
  void stop() {
    if (!loop_) return;
    loop_->stop();
    if (thread_.joinable()) thread_.join();
    loop_.reset();
  }
  /// The loop object (nullptr before make() and after stop()); its thread-safe members only.
  [[nodiscard]] Loop* get() const { return loop_.get(); }
  [[nodiscard]] bool running() const { return loop_ != nullptr; }

 private:
  std::unique_ptr<Loop> loop_;
  std::thread thread_;
  bool started_ = false;
};

/// Emulator::start() of a server whose `Impl` (made from `args`) has `listen()` (an error or
/// nullopt), `bound_port()` and `run(FrameProvider)`: checks the rate, binds, and runs it on
/// `loop`'s thread; `port` gets the bound port.
template <typename Impl, typename... Args>
[[nodiscard]] std::optional<std::string> start_emulator(LoopThread<Impl>& loop, std::uint16_t& port,
                                                        double rate_hz,
                                                        Emulator::FrameProvider provider,
                                                        Args&&... args) {
  if (loop.get() != nullptr) return "already started";
  if (!(rate_hz > 0.0 && rate_hz <= 10000.0)) return "rate must be in (0, 10000] Hz";
  Impl& impl = loop.make(std::forward<Args>(args)...);
  if (auto err = impl.listen()) {
    loop.stop();
    return err;
  }
  port = impl.bound_port();
  loop.run([p = std::move(provider)](Impl& i) mutable { i.run(std::move(p)); });
  return std::nullopt;
}

}  // namespace mocaplink::sources

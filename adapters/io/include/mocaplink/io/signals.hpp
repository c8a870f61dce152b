// A request to stop → a clean stop on the event loop (issue 5: last datagrams flushed, files
// closed). Linux: SIGINT and SIGTERM. Windows: Ctrl-C, Ctrl-Break, and the console window being
// closed (or the user logging off, or the machine shutting down), which Windows otherwise ends by
// killing the process a few seconds later. The handler runs on the io_context's thread, never in
// signal or console-handler context, so it may do anything the loop may do.
#pragma once

#include <chrono>
#include <functional>
#include <string_view>

#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

namespace mocaplink::io {

/// Listens for stop requests while alive. `on_signal(what, count)` is called on the loop thread for
/// every request (`what` names it for logs: "SIGINT", "SIGTERM", "Ctrl-Break", "console close",
/// …; count = 1 for the first): the owner stops cleanly on the first and may give up waiting on a
/// later one. Construct before the loop runs; destroying it restores the default dispositions (on
/// Windows, a console close waits for that, up to 10 s, before the process may end). One at a
/// time per process. Not thread-safe (loop thread only).
class StopSignals {
 public:
  using Handler = std::function<void(std::string_view what, int count)>;
  StopSignals(asio::io_context& loop, Handler on_signal);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Requests received so far.
  [[nodiscard]] int count() const noexcept { return count_; }

 private:
  void arm();
  void deliver(std::string_view what);

  asio::io_context& loop_;
  asio::signal_set signals_;
  Handler on_signal_;
  int count_ = 0;
};

#ifdef _WIN32
namespace detail {
/// The console control handler StopSignals installs (exposed for tests: Windows cannot be asked
/// to send a console close). For a close, log-off or shutdown with a StopSignals alive: hands the
/// request to its loop, waits until it is destroyed (up to 10 s), then waits `exit_grace` more —
/// the process normally ends meanwhile, through main, with every file closed — and returns TRUE
/// (Windows then ends the process). FALSE for anything else (Ctrl-C and Ctrl-Break go on to the C
/// runtime, which raises SIGINT / SIGBREAK) or without a StopSignals.
int handle_console_event(unsigned long event,
                         std::chrono::milliseconds exit_grace = std::chrono::seconds(10));
}  // namespace detail
#endif

}  // namespace mocaplink::io

// SIGINT / SIGTERM → a clean stop on the event loop (issue 5: last datagrams flushed, files
// closed). The handler runs on the io_context's thread, never in signal context, so it may do
// anything the loop may do.
#pragma once

#include <functional>

#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

namespace mocaplink::io {

/// Listens for SIGINT and SIGTERM while alive. `on_signal(signal_number, count)` is called on the
/// loop thread for every signal received (count = 1 for the first): the owner stops cleanly on
/// the first and may give up waiting on a later one. Construct before the loop runs; destroying
/// it restores the default dispositions. Not thread-safe (loop thread only).
class StopSignals {
 public:
  using Handler = std::function<void(int signal_number, int count)>;
  StopSignals(asio::io_context& loop, Handler on_signal);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Signals received so far.
  [[nodiscard]] int count() const noexcept { return count_; }

 private:
  void arm();

  asio::signal_set signals_;
  Handler on_signal_;
  int count_ = 0;
};

}  // namespace mocaplink::io

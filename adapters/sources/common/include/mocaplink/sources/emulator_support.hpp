// What every `mocaplink serve` emulator needs besides its protocol: the frame schedule at --rate
// and, for TCP servers, a listening socket. Header-only; include it from a target that links asio.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <asio.hpp>

#include "mocaplink/sources/loop_thread.hpp"

namespace mocaplink::sources {

/// The drift-free schedule of an emulator's frames: tick n is due at start + n × period. After a
/// stall of more than 5 periods it skips ahead (the skipped ticks are dropped frames) instead of
/// bursting.
class TickSchedule {
 public:
  using Clock = std::chrono::steady_clock;

  TickSchedule(double rate_hz, Clock::time_point start)
      : period_(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(1.0 / rate_hz))),
        start_(start) {}

  [[nodiscard]] std::uint64_t tick() const { return tick_; }
  [[nodiscard]] Clock::time_point due() const {
    return start_ + period_ * static_cast<std::int64_t>(tick_);
  }
  /// Moves to the next tick (or further, after a stall) as of `now`.
  void advance(Clock::time_point now) {
    ++tick_;
    const auto behind = now - due();
    if (behind > period_ * 5) tick_ += static_cast<std::uint64_t>(behind / period_);
  }

 private:
  Clock::duration period_;
  Clock::time_point start_;
  std::uint64_t tick_ = 0;
};

/// Opens, binds (SO_REUSEADDR) and listens on host:port; an error as one line.
[[nodiscard]] inline std::optional<std::string> listen_tcp(asio::ip::tcp::acceptor& acceptor,
                                                           const std::string& host,
                                                           std::uint16_t port) {
  using asio::ip::tcp;
  asio::error_code ec;
  const auto address = asio::ip::make_address(host, ec);
  if (ec) return "bad listen address '" + host + "': " + ec.message();
  const tcp::endpoint endpoint(address, port);
  if (acceptor.open(endpoint.protocol(), ec); ec) return "socket: " + ec.message();
  if (acceptor.set_option(tcp::acceptor::reuse_address(true), ec); ec) {
    return "SO_REUSEADDR: " + ec.message();
  }
  if (acceptor.bind(endpoint, ec); ec) {
    return "cannot listen on " + host + ":" + std::to_string(port) + ": " + ec.message();
  }
  if (acceptor.listen(asio::socket_base::max_listen_connections, ec); ec) {
    return "listen: " + ec.message();
  }
  return std::nullopt;
}

/// Emulator::start for an emulator whose Impl (its event loop) has open() (bind; an error as one
/// line), local_port(), run() and stop(): checks the rate, opens, and runs it on `worker`.
template <typename Impl>
[[nodiscard]] std::optional<std::string> start_emulator(LoopThread<Impl>& worker, double rate_hz,
                                                        std::unique_ptr<Impl> impl,
                                                        std::uint16_t& port) {
  if (worker.running()) return "already started";
  if (!(rate_hz > 0.0 && rate_hz <= 10000.0)) return "rate must be in (0, 10000] Hz";
  if (auto error = impl->open()) return error;
  port = impl->local_port();
  worker.start(std::move(impl));
  return std::nullopt;
}

}  // namespace mocaplink::sources

// What a dashboard client may hold, so that idle, slow and crowding clients (a stuck tab, a port
// scanner, a phone on bad Wi-Fi) never lock the operator out (issue 15, docs/api.md
// "Connections"): a cap on the connections one client address holds at once, and a deadline on
// the time a whole request may take to arrive. Pure logic with time passed in; the server
// (dashboard_server.cpp) applies it to its sockets.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

namespace mocaplink::web {

/// Connections open per client address, at most `per_client` each. Thread-safe: every member may
/// be called from any connection thread.
class ClientSlots {
 public:
  /// `per_client` ≥ 1.
  explicit ClientSlots(std::size_t per_client);

  /// Takes one slot for `address` (the numeric IP the connection comes from). False when the
  /// address already holds `per_client`: the connection is refused and counted in refused().
  [[nodiscard]] bool try_acquire(const std::string& address);
  /// Gives back a slot try_acquire() granted to `address`.
  void release(const std::string& address);

  [[nodiscard]] std::size_t per_client() const { return per_client_; }
  /// Connections holding a slot now, over all addresses.
  [[nodiscard]] std::size_t open() const;
  /// Connections refused since construction.
  [[nodiscard]] std::uint64_t refused() const;

 private:
  const std::size_t per_client_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::size_t> open_by_address_;
  std::size_t open_ = 0;
  std::uint64_t refused_ = 0;
};

/// The time one request (request line, headers and body) may take to arrive, counted from its
/// first byte, plus the longest silence allowed between its bytes. A client sending one byte a
/// second never falls silent for long, but still runs out of `total`. Plain value type.
class RequestDeadline {
 public:
  using Clock = std::chrono::steady_clock;

  /// `total` and `silence` > 0.
  RequestDeadline(std::chrono::milliseconds total, std::chrono::milliseconds silence);

  /// The request's first byte arrived at `now`.
  void start(Clock::time_point now) { deadline_ = now + total_; }

  /// How long the next read may wait for more bytes of the request at `now`: the silence limit,
  /// or what is left of the total when that is shorter. nullopt once the total has run out (the
  /// request took too long; the connection is answered 408 and closed).
  [[nodiscard]] std::optional<std::chrono::milliseconds> next_wait(Clock::time_point now) const;

 private:
  std::chrono::milliseconds total_;
  std::chrono::milliseconds silence_;
  Clock::time_point deadline_{};
};

}  // namespace mocaplink::web

// The bounded write backlog of a stream link (TCP, serial): frames accepted by send() wait here
// while one asynchronous write is in flight. Two buffers — `pending` (appended to) and `in_flight`
// (being written) — so appending never moves bytes the OS is reading. Bounded by a byte budget:
// on a link slower than the pose stream, new frames are refused (and counted by the link) rather
// than delivered seconds late.
// Not thread-safe (owned by one link on the loop thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mocaplink::io {

class LinkBacklog {
 public:
  /// At most `max_bytes` in pending + in flight.
  explicit LinkBacklog(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  /// Queues one frame; false (nothing queued) if it would exceed the budget.
  [[nodiscard]] bool append(std::span<const std::uint8_t> frame);
  /// True when a write is in flight.
  [[nodiscard]] bool writing() const noexcept { return writing_; }
  [[nodiscard]] bool has_pending() const noexcept { return !pending_.empty(); }
  /// Starts a write: pending becomes in flight (requires !writing() && has_pending()). The span
  /// stays valid until finish_write() or clear().
  [[nodiscard]] std::span<const std::uint8_t> begin_write();
  /// The in-flight write completed; returns how many frames it held.
  std::uint64_t finish_write() noexcept;
  /// Drops everything (connection lost); returns how many frames were dropped.
  std::uint64_t clear() noexcept;
  /// Bytes pending + in flight.
  [[nodiscard]] std::size_t bytes() const noexcept { return pending_.size() + in_flight_.size(); }

 private:
  std::size_t max_bytes_;
  std::vector<std::uint8_t> pending_;
  std::vector<std::uint8_t> in_flight_;
  std::uint64_t pending_frames_ = 0;
  std::uint64_t in_flight_frames_ = 0;
  bool writing_ = false;
};

}  // namespace mocaplink::io

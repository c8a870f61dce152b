// Common behaviour of the byte-stream links (TCP, serial): open with back-off, one read loop
// feeding the stream parser, a bounded write backlog (link_backlog.hpp), reopen after any error,
// and a bounded linger on close so the last frames leave before the process exits.
//
//   connecting ──open ok──▶ up ──read/write error, EOF──▶ down ──back-off──▶ (open again) ...
//
// While the link is not up, send() drops frames and counts them (dropped_down): a pose delivered
// after a reconnect would be stale, and MAVLink has no retransmission to expect it.
// Subclasses provide the transport through the protected hooks. Threading as in link.hpp.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <system_error>

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

#include "mocaplink/io/link.hpp"
#include "mocaplink/io/link_backlog.hpp"
#include "mocaplink/io/poses_first.hpp"

namespace mocaplink::io {

class StreamLink : public Link {
 public:
  ~StreamLink() override;

  void start(FrameHandler on_frame, StateHandler on_state) final;
  bool send(std::span<const std::uint8_t> frame) final;
  bool send_forwarded(std::span<const std::uint8_t> frame) final;
  void set_pose_period(std::chrono::nanoseconds period) final { gate_.set_pose_period(period); }
  [[nodiscard]] std::size_t forwarded_queued_bytes() const noexcept final {
    return gate_.queued_bytes();
  }
  [[nodiscard]] std::optional<double> capacity_bytes_per_second() const noexcept final {
    return bytes_per_second_ > 0.0 ? std::optional<double>(bytes_per_second_) : std::nullopt;
  }
  void close(std::chrono::milliseconds linger) final;
  [[nodiscard]] std::size_t backlog_bytes() const noexcept final { return backlog_.bytes(); }

 protected:
  using IoHandler = std::function<void(const std::error_code& error, std::size_t bytes)>;
  using OpenHandler = std::function<void(const std::error_code& error, const std::string& detail)>;

  /// `bytes_per_second`: the transport's speed when known (serial: baud / 10), for the
  /// poses-first rule; 0 for unknown (TCP).
  StreamLink(asio::io_context& loop, LinkOptions options, double bytes_per_second = 0.0);

  /// Begin opening/connecting; call `done` exactly once (on the loop thread). `detail` names the
  /// endpoint (for the state message).
  virtual void async_open(OpenHandler done) = 0;
  /// Write all of `bytes` (asio::async_write semantics).
  virtual void async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) = 0;
  /// Read some bytes into `buffer`.
  virtual void async_read_some(std::span<std::uint8_t> buffer, IoHandler done) = 0;
  /// Close the transport (cancels its pending operations). Must be safe when already closed.
  virtual void close_transport() noexcept = 0;
  /// The link closed for good (close()): release what outlives one connection (a listener).
  virtual void release() noexcept {}
  /// Bytes written but still held by the OS (a socket's send buffer, a tty's output queue), where
  /// the platform tells (Linux: SIOCOUTQ / TIOCOUTQ); nullopt elsewhere.
  [[nodiscard]] virtual std::optional<std::size_t> unsent_bytes() const noexcept {
    return std::nullopt;
  }
  /// How often a waiting forwarded frame looks again while the OS still holds too much.
  static constexpr std::chrono::milliseconds kUnsentPoll{2};
  /// Drops the current connection (as a read error would) and opens again at once, without the
  /// back-off: a listening link whose vehicle connected anew.
  void reconnect_now(const std::string& why);

  asio::io_context& loop_;

 private:
  void open();
  void on_opened(std::uint64_t generation, const std::error_code& error, const std::string& detail);
  void read();
  void kick_write();
  /// Writes the next forwarded frame when the own queue is empty and the rule allows it.
  void pump_forwarded();
  void lose_connection(const std::string& why, bool at_once = false);
  void finish_close();

  LinkBacklog backlog_;
  double bytes_per_second_;
  PosesFirst gate_;  // forwarded frames waiting for their turn
  asio::steady_timer retry_timer_;
  asio::steady_timer forward_timer_;
  asio::steady_timer linger_timer_;
  std::uint64_t generation_ = 0;  // bumped per connection; handlers of older ones are ignored
  bool closing_ = false;
  std::array<std::uint8_t, 4096> read_buffer_{};
};

}  // namespace mocaplink::io

// What both UDP links share (UdpLink: udp://, UdpInLink: udpin://): one non-blocking socket, its
// open / retry cycle on the reconnect schedule, one receive loop feeding the datagram parser, and
// the closing. The subclasses decide how the socket is opened (connected to the vehicle, or bound
// to listen) and where sends go.
// Threading as in link.hpp: sends are synchronous (sends_in_place).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <asio/steady_timer.hpp>

#include "mocaplink/io/link.hpp"

namespace mocaplink::io {

class UdpSocketLink : public Link {
 public:
  ~UdpSocketLink() override;

  void start(FrameHandler on_frame, StateHandler on_state) final;
  void close(std::chrono::milliseconds linger) final;
  [[nodiscard]] bool sends_in_place() const noexcept final { return true; }
  [[nodiscard]] std::size_t backlog_bytes() const noexcept final { return 0; }

  /// The socket's local endpoint (tests: where a vehicle must send). Unspecified before it opens.
  [[nodiscard]] asio::ip::udp::endpoint local_endpoint() const;

 protected:
  UdpSocketLink(asio::io_context& loop, LinkOptions options);

  /// Opens the socket (first at start(), then after each schedule_retry).
  virtual void open() = 0;
  /// One datagram arrived from `from` (valid only during the call).
  virtual void on_datagram(std::span<const std::uint8_t> bytes,
                           const asio::ip::udp::endpoint& from) = 0;

  /// The link is `down` for `why`; open() again on the reconnect schedule.
  void schedule_retry(const std::string& why);
  /// Closes the socket after a failed open, then schedule_retry(why).
  void fail_open(const std::string& why);
  /// Starts the receive loop (once the socket is open).
  void receive();
  /// Counts a send that failed with `error` by its kind (full buffer, ICMP, other).
  void count_send_error(const std::error_code& error);

  asio::io_context& loop_;
  asio::ip::udp::socket socket_;

 private:
  asio::steady_timer retry_timer_;
  asio::ip::udp::endpoint sender_;  // of the datagram being received
  // Largest UDP payload: a datagram never holds more, and a smaller buffer would truncate a
  // datagram packed with several frames. On the heap and not zeroed: the OS makes a page of it
  // resident only once a datagram reaches it (fresh heap memory), so a vehicle that sends one
  // frame per datagram costs about a page rather than 64 KiB (peak RSS at 1000 vehicles,
  // docs/performance.md), and the link object stays small.
  static constexpr std::size_t kReceiveBufferSize = 65536;
  std::unique_ptr<std::uint8_t[]> receive_buffer_ =
      std::make_unique_for_overwrite<std::uint8_t[]>(kReceiveBufferSize);
};

}  // namespace mocaplink::io

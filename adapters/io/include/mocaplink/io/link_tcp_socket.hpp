// What both TCP links share (TcpLink: tcp://, TcpInLink: tcpin://): the vehicle's connection as
// one asio TCP socket, and the stream hooks over it (write all, read some, close, unsent bytes).
// The subclasses decide how the connection comes to be (connect out, or accept) in async_open.
// Threading as in link.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>

#include "mocaplink/io/link_stream.hpp"

namespace mocaplink::io {

class TcpSocketLink : public StreamLink {
 protected:
  TcpSocketLink(asio::io_context& loop, LinkOptions options);

  /// The connection is open: TCP_NODELAY, so a pose frame leaves now, not when Nagle's algorithm
  /// has collected a segment.
  void set_no_delay();

  void async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) final;
  void async_read_some(std::span<std::uint8_t> buffer, IoHandler done) final;
  void close_transport() noexcept final;
  [[nodiscard]] std::optional<std::size_t> unsent_bytes() const noexcept final;

  asio::ip::tcp::socket socket_;  // the vehicle's connection
};

}  // namespace mocaplink::io

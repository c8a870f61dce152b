#include "mocaplink/io/link_tcp_socket.hpp"

#include <utility>

#include <asio/write.hpp>

#include "unsent.hpp"

namespace mocaplink::io {

TcpSocketLink::TcpSocketLink(asio::io_context& loop, LinkOptions options)
    : StreamLink(loop, std::move(options)), socket_(loop) {}

void TcpSocketLink::set_no_delay() {
  std::error_code ignored;
  socket_.set_option(asio::ip::tcp::no_delay(true), ignored);
}

void TcpSocketLink::async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) {
  asio::async_write(socket_, asio::buffer(bytes.data(), bytes.size()), std::move(done));
}

void TcpSocketLink::async_read_some(std::span<std::uint8_t> buffer, IoHandler done) {
  socket_.async_read_some(asio::buffer(buffer.data(), buffer.size()), std::move(done));
}

void TcpSocketLink::close_transport() noexcept {
  std::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

std::optional<std::size_t> TcpSocketLink::unsent_bytes() const noexcept {
  if (!socket_.is_open()) return std::nullopt;
  return detail::unsent_bytes(const_cast<decltype(socket_)&>(socket_).native_handle());
}

}  // namespace mocaplink::io

#include "mocaplink/io/link_tcp.hpp"

#include <utility>

#include <asio/connect.hpp>
#include <asio/post.hpp>
#include <asio/write.hpp>

#include "resolve.hpp"
#include "unsent.hpp"

namespace mocaplink::io {

TcpLink::TcpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options)
    : StreamLink(loop, std::move(options)), host_(std::move(host)), port_(port), socket_(loop) {}

TcpLink::~TcpLink() {
  close_transport();
}

std::string TcpLink::url() const {
  return "tcp://" + detail::host_port_text(host_, port_);
}

void TcpLink::async_open(OpenHandler done) {
  detail::resolve_async<asio::ip::tcp>(
      loop_, host_, port_, liveness(),
      [this, done = std::move(done)](const std::error_code& error,
                                     const std::vector<asio::ip::tcp::endpoint>& endpoints) {
        if (state() == TransportState::closed) return;  // closed while a name was being resolved
        if (error || endpoints.empty()) {
          // Report through the loop, never re-entrantly from start().
          asio::post(loop_, [done, error, host = host_] {
            done(error ? error : asio::error::host_not_found, "cannot resolve " + host);
          });
          return;
        }
        connect(endpoints, done);
      });
}

void TcpLink::connect(const std::vector<asio::ip::tcp::endpoint>& endpoints, OpenHandler done) {
  close_transport();
  asio::async_connect(socket_, endpoints,
                      [this, done = std::move(done)](const std::error_code& error,
                                                     const asio::ip::tcp::endpoint& /*endpoint*/) {
                        if (!error) {
                          std::error_code ignored;
                          socket_.set_option(asio::ip::tcp::no_delay(true), ignored);
                        }
                        done(error, error ? "cannot connect to " + url() : "connected to " + url());
                      });
}

void TcpLink::async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) {
  asio::async_write(socket_, asio::buffer(bytes.data(), bytes.size()), std::move(done));
}

void TcpLink::async_read_some(std::span<std::uint8_t> buffer, IoHandler done) {
  socket_.async_read_some(asio::buffer(buffer.data(), buffer.size()), std::move(done));
}

void TcpLink::close_transport() noexcept {
  std::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
}

std::optional<std::size_t> TcpLink::unsent_bytes() const noexcept {
  if (!socket_.is_open()) return std::nullopt;
  return detail::unsent_bytes(const_cast<decltype(socket_)&>(socket_).native_handle());
}

}  // namespace mocaplink::io

#include "mocaplink/io/link_tcp.hpp"

#include <utility>

#include <asio/connect.hpp>
#include <asio/post.hpp>

#include "resolve.hpp"

namespace mocaplink::io {

TcpLink::TcpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options)
    : TcpSocketLink(loop, std::move(options)), host_(std::move(host)), port_(port) {}

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
                        if (!error) set_no_delay();
                        done(error, error ? "cannot connect to " + url() : "connected to " + url());
                      });
}

}  // namespace mocaplink::io

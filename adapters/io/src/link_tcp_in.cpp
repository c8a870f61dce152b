#include "mocaplink/io/link_tcp_in.hpp"

#include <utility>

#include <asio/post.hpp>

#include "resolve.hpp"

namespace mocaplink::io {
namespace {

std::string peer_text(const asio::ip::tcp::socket& socket) {
  std::error_code ec;
  const auto peer = socket.remote_endpoint(ec);
  return ec ? std::string("an unknown address")
            : detail::host_port_text(peer.address().to_string(), peer.port());
}

}  // namespace

TcpInLink::TcpInLink(asio::io_context& loop, std::string host, std::uint16_t port,
                     LinkOptions options)
    : TcpSocketLink(loop, std::move(options)),
      host_(std::move(host)),
      port_(port),
      acceptor_(loop),
      incoming_(loop),
      pending_(loop) {}

TcpInLink::~TcpInLink() {
  close_transport();
  release();
}

std::string TcpInLink::url() const {
  return "tcpin://" + detail::host_port_text(host_, port_);
}

asio::ip::tcp::endpoint TcpInLink::local_endpoint() const {
  std::error_code ec;
  auto endpoint = acceptor_.local_endpoint(ec);
  return ec ? asio::ip::tcp::endpoint{} : endpoint;
}

bool TcpInLink::listen(std::error_code& error) {
  if (acceptor_.is_open()) return true;
  const auto local = detail::local_endpoint<asio::ip::tcp>(host_, port_, false, error);
  if (!error) acceptor_.open(local.protocol(), error);
#ifndef _WIN32
  // A restarted mocaplink must be able to listen again while the last connection is in
  // TIME_WAIT. (On Windows SO_REUSEADDR would let another program take the port too.)
  if (!error) acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true), error);
#endif
  if (!error) acceptor_.bind(local, error);
  if (!error) acceptor_.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    std::error_code ignored;
    acceptor_.close(ignored);
    return false;
  }
  return true;
}

void TcpInLink::async_open(OpenHandler done) {
  std::error_code error;
  if (!listen(error)) {
    asio::post(loop_, [done = std::move(done), error, url = url()] {
      done(error, "cannot listen on " + url);
    });
    return;
  }
  if (pending_.is_open()) {
    adopt(std::move(done));
    return;
  }
  waiting_ = std::move(done);
  if (!accepting_) accept();
}

void TcpInLink::adopt(OpenHandler done) {
  socket_ = std::move(pending_);
  pending_ = asio::ip::tcp::socket(loop_);
  set_no_delay();
  asio::post(loop_, [done = std::move(done), detail = options_.peer + " connected from " +
                                                      peer_text(socket_) + " to " +
                                                      url()] { done(std::error_code{}, detail); });
}

void TcpInLink::accept() {
  accepting_ = true;
  acceptor_.async_accept(incoming_, [this](const std::error_code& error) {
    accepting_ = false;
    if (error == asio::error::operation_aborted || !acceptor_.is_open()) return;
    if (error) {  // a connection that died before it was accepted, out of descriptors, ...
      ++counters_.receive_errors;
      accept();
      return;
    }
    std::error_code ignored;
    pending_.close(ignored);  // an older connection nobody adopted: the newest one counts
    pending_ = std::move(incoming_);
    incoming_ = asio::ip::tcp::socket(loop_);
    if (waiting_) {
      adopt(std::exchange(waiting_, nullptr));
    } else if (state() == TransportState::up) {
      reconnect_now(options_.peer + " connected again from " + peer_text(pending_) +
                    ": that connection replaces this one");
    }  // else: down, between connections; open() adopts it after the back-off
    accept();
  });
}

void TcpInLink::release() noexcept {
  std::error_code ignored;
  waiting_ = nullptr;
  acceptor_.close(ignored);
  pending_.close(ignored);
  incoming_.close(ignored);
}

}  // namespace mocaplink::io

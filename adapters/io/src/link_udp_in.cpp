#include "mocaplink/io/link_udp_in.hpp"

#include <utility>

#include "resolve.hpp"

namespace mocaplink::io {
namespace {

std::string endpoint_text(const asio::ip::udp::endpoint& e) {
  return detail::host_port_text(e.address().to_string(), e.port());
}

}  // namespace

using detail::is_refused;

UdpInLink::UdpInLink(asio::io_context& loop, std::string host, std::uint16_t port,
                     LinkOptions options)
    : Link(std::move(options)),
      loop_(loop),
      host_(std::move(host)),
      port_(port),
      socket_(loop),
      retry_timer_(loop) {}

UdpInLink::~UdpInLink() {
  std::error_code ignored;
  retry_timer_.cancel();
  socket_.close(ignored);
}

std::string UdpInLink::url() const {
  return "udpin://" + detail::host_port_text(host_, port_);
}

asio::ip::udp::endpoint UdpInLink::local_endpoint() const {
  std::error_code ec;
  auto endpoint = socket_.local_endpoint(ec);
  return ec ? asio::ip::udp::endpoint{} : endpoint;
}

void UdpInLink::start(FrameHandler on_frame, StateHandler on_state) {
  set_handlers(std::move(on_frame), std::move(on_state));
  open();
}

void UdpInLink::open() {
  if (state() == TransportState::closed) return;
  std::error_code ec;
  const auto local = detail::local_endpoint<asio::ip::udp>(host_, port_, false, ec);
  if (!ec) socket_.open(local.protocol(), ec);
  if (!ec) socket_.non_blocking(true, ec);
  if (!ec) socket_.bind(local, ec);
  if (ec) {
    std::error_code ignored;
    socket_.close(ignored);
    schedule_retry("cannot listen on " + url() + ": " + ec.message() +
                   (ec == asio::error::address_in_use
                        ? " (another program, or another mocaplink process, owns the port)"
                        : ""));
    return;
  }
  reset_backoff();
  ++counters_.connects;
  // `connecting` until the vehicle has spoken: nothing can be sent before.
  const std::string listening =
      "listening on " + url() + "; waiting for " + options_.peer + " to speak";
  if (state() == TransportState::connecting) {
    report_state(listening);
  } else {
    set_state(TransportState::connecting, listening);
  }
  receive();
}

void UdpInLink::schedule_retry(const std::string& why) {
  set_state(TransportState::down, why);
  retry_timer_.expires_after(next_backoff());
  retry_timer_.async_wait([this](const std::error_code& error) {
    if (!error) open();
  });
}

void UdpInLink::receive() {
  socket_.async_receive_from(
      asio::buffer(receive_buffer_.get(), kReceiveBufferSize), sender_,
      [this](const std::error_code& error, std::size_t n) {
        if (error == asio::error::operation_aborted || state() == TransportState::closed) return;
        if (error) {
          if (is_refused(error)) {
            ++counters_.refused;
          } else {
            ++counters_.receive_errors;
          }
        } else {
          on_datagram(n);
        }
        if (socket_.is_open()) receive();
      });
}

void UdpInLink::on_datagram(std::size_t n) {
  const asio::ip::udp::endpoint from = sender_;  // the handler below may receive again
  if (receive_datagram(std::span<const std::uint8_t>(receive_buffer_.get(), n)) == 0) return;
  if (has_peer_ && from == peer_) return;
  const bool moved = has_peer_;
  const std::string was = moved ? endpoint_text(peer_) : std::string();
  peer_ = from;
  has_peer_ = true;
  if (moved) {
    report_state(options_.peer + " now speaks from " + endpoint_text(peer_) + " (was " + was +
                 "): answering there");
  } else {
    set_state(TransportState::up, options_.peer + " spoke from " + endpoint_text(peer_) + " to " +
                                      url() + ": answering there");
  }
}

bool UdpInLink::send(std::span<const std::uint8_t> frame) {
  if (state() != TransportState::up || !has_peer_) {
    ++counters_.dropped_down;
    return false;
  }
  std::error_code ec;
  socket_.send_to(asio::buffer(frame.data(), frame.size()), peer_, 0, ec);
  if (!ec) {
    ++counters_.frames_sent;
    counters_.bytes_sent += frame.size();
    return true;
  }
  if (ec == asio::error::would_block || ec == asio::error::no_buffer_space) {
    ++counters_.dropped_backlog;
  } else if (is_refused(ec)) {
    ++counters_.refused;
  } else {
    ++counters_.send_errors;
  }
  return false;
}

void UdpInLink::close(std::chrono::milliseconds /*linger*/) {
  if (state() == TransportState::closed) return;
  set_state(TransportState::closed, "closed");
  std::error_code ignored;
  retry_timer_.cancel();
  socket_.close(ignored);
}

}  // namespace mocaplink::io

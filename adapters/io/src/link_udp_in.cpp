#include "mocaplink/io/link_udp_in.hpp"

#include <utility>

#include "resolve.hpp"

namespace mocaplink::io {
namespace {

std::string endpoint_text(const asio::ip::udp::endpoint& e) {
  return detail::host_port_text(e.address().to_string(), e.port());
}

}  // namespace

UdpInLink::UdpInLink(asio::io_context& loop, std::string host, std::uint16_t port,
                     LinkOptions options)
    : UdpSocketLink(loop, std::move(options)), host_(std::move(host)), port_(port) {}

std::string UdpInLink::url() const {
  return "udpin://" + detail::host_port_text(host_, port_);
}

void UdpInLink::open() {
  if (state() == TransportState::closed) return;
  std::error_code ec;
  const auto local = detail::local_endpoint<asio::ip::udp>(host_, port_, false, ec);
  if (!ec) socket_.open(local.protocol(), ec);
  if (!ec) socket_.non_blocking(true, ec);
  if (!ec) socket_.bind(local, ec);
  if (ec) {
    fail_open("cannot listen on " + url() + ": " + ec.message() +
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

void UdpInLink::on_datagram(std::span<const std::uint8_t> bytes,
                            const asio::ip::udp::endpoint& from) {
  if (receive_datagram(bytes) == 0) return;
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
  count_send_error(ec);
  return false;
}

}  // namespace mocaplink::io

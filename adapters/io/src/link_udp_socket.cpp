#include "mocaplink/io/link_udp_socket.hpp"

#include <utility>

#include "resolve.hpp"

namespace mocaplink::io {

UdpSocketLink::UdpSocketLink(asio::io_context& loop, LinkOptions options)
    : Link(std::move(options)), loop_(loop), socket_(loop), retry_timer_(loop) {}

UdpSocketLink::~UdpSocketLink() {
  std::error_code ignored;
  retry_timer_.cancel();
  socket_.close(ignored);
}

void UdpSocketLink::start(FrameHandler on_frame, StateHandler on_state) {
  set_handlers(std::move(on_frame), std::move(on_state));
  open();
}

asio::ip::udp::endpoint UdpSocketLink::local_endpoint() const {
  std::error_code ec;
  auto endpoint = socket_.local_endpoint(ec);
  return ec ? asio::ip::udp::endpoint{} : endpoint;
}

void UdpSocketLink::schedule_retry(const std::string& why) {
  set_state(TransportState::down, why);
  retry_timer_.expires_after(next_backoff());
  retry_timer_.async_wait([this](const std::error_code& error) {
    if (!error) open();
  });
}

void UdpSocketLink::fail_open(const std::string& why) {
  std::error_code ignored;
  socket_.close(ignored);
  schedule_retry(why);
}

void UdpSocketLink::receive() {
  socket_.async_receive_from(
      asio::buffer(receive_buffer_.get(), kReceiveBufferSize), sender_,
      [this](const std::error_code& error, std::size_t n) {
        if (error == asio::error::operation_aborted || state() == TransportState::closed) return;
        if (error) {
          if (detail::is_refused(error)) {
            ++counters_.refused;  // an earlier datagram met an ICMP port unreachable
          } else {
            ++counters_.receive_errors;
          }
        } else {
          const asio::ip::udp::endpoint from = sender_;  // on_datagram may receive again
          on_datagram(std::span<const std::uint8_t>(receive_buffer_.get(), n), from);
        }
        if (socket_.is_open()) receive();
      });
}

void UdpSocketLink::count_send_error(const std::error_code& error) {
  if (error == asio::error::would_block || error == asio::error::no_buffer_space) {
    ++counters_.dropped_backlog;
  } else if (detail::is_refused(error)) {
    ++counters_.refused;
  } else {
    ++counters_.send_errors;
  }
}

void UdpSocketLink::close(std::chrono::milliseconds /*linger*/) {
  if (state() == TransportState::closed) return;
  set_state(TransportState::closed, "closed");
  std::error_code ignored;
  retry_timer_.cancel();
  socket_.close(ignored);
}

}  // namespace mocaplink::io

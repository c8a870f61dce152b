#include "mocaplink/io/link_udp.hpp"

#ifdef __linux__
#include <sys/socket.h>
#include <sys/uio.h>
#endif

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

#include <asio/ip/address.hpp>

#include "resolve.hpp"

namespace mocaplink::io {

using detail::is_refused;

UdpLink::UdpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options,
                 std::optional<config::HostPort> bind)
    : UdpSocketLink(loop, std::move(options)),
      host_(std::move(host)),
      port_(port),
      bind_(std::move(bind)) {}

std::string UdpLink::url() const {
  return "udp://" + detail::host_port_text(host_, port_) +
         (bind_ ? "?bind=" + detail::host_port_text(bind_->host, bind_->port) : "");
}

void UdpLink::open() {
  if (state() == TransportState::closed) return;
  detail::resolve_async<asio::ip::udp>(
      loop_, host_, port_, liveness(),
      [this](const std::error_code& error, const std::vector<asio::ip::udp::endpoint>& found) {
        if (state() == TransportState::closed) return;
        if (error || found.empty()) {
          schedule_retry("cannot resolve " + host_ + ": " +
                         (error ? error.message() : "no address"));
          return;
        }
        connect(found.front());
      });
}

void UdpLink::connect(const asio::ip::udp::endpoint& remote) {
  std::error_code ec;
  socket_.close(ec);
  socket_.open(remote.protocol(), ec);
  if (!ec) socket_.non_blocking(true, ec);
  if (!ec && bind_) {
    const auto local = detail::local_endpoint<asio::ip::udp>(
        bind_->host, bind_->port, remote.protocol().family() == asio::ip::udp::v6().family(), ec);
    if (!ec) socket_.bind(local, ec);
    if (ec) {
      fail_open("cannot send from " + detail::host_port_text(bind_->host, bind_->port) + " to " +
                url() + ": " + ec.message() +
                (ec == asio::error::address_in_use
                     ? " (another program, or another mocaplink process, owns the port)"
                     : ""));
      return;
    }
  }
  if (!ec) socket_.connect(remote, ec);
  if (ec) {
    fail_open("cannot open a UDP socket to " + url() + ": " + ec.message());
    return;
  }
  reset_backoff();
  ++counters_.connects;
  set_state(TransportState::up,
            "sending to " + url() + " from port " + std::to_string(local_endpoint().port()));
  receive();
}

void UdpLink::on_datagram(std::span<const std::uint8_t> bytes,
                          const asio::ip::udp::endpoint& /*from*/) {
  (void)receive_datagram(bytes);  // connected: only the vehicle's address reaches the socket
}

bool UdpLink::send(std::span<const std::uint8_t> frame) {
  if (state() != TransportState::up) {
    ++counters_.dropped_down;
    return false;
  }
  std::error_code ec;
  // A pending ICMP error is reported by (and cleared by) the first call that meets it, without
  // sending: count it and try this frame once more.
  for (int attempt = 0; attempt < 2; ++attempt) {
    socket_.send(asio::buffer(frame.data(), frame.size()), 0, ec);
    if (!is_refused(ec)) break;
    ++counters_.refused;
  }
  if (!ec) {
    ++counters_.frames_sent;
    counters_.bytes_sent += frame.size();
    return true;
  }
  if (!is_refused(ec)) count_send_error(ec);  // a refusal was counted above
  return false;
}

std::size_t UdpLink::send_batch(std::span<const std::span<const std::uint8_t>> frames) {
  if (state() != TransportState::up) {
    counters_.dropped_down += frames.size();
    return 0;
  }
  // One frame (a pose, most frames): send() is one system call too, and cheaper than sendmmsg's.
  if (frames.size() == 1) return send(frames.front()) ? 1U : 0U;
#ifdef __linux__
  std::size_t next = 0;  // the first frame not handed to the OS yet
  std::size_t sent = 0;
  while (next < frames.size()) {
    const std::size_t n = std::min(frames.size() - next, kMaxBatch);
    std::array<iovec, kMaxBatch> iov{};
    std::array<mmsghdr, kMaxBatch> msgs{};
    for (std::size_t i = 0; i < n; ++i) {
      const auto& frame = frames[next + i];
      iov[i].iov_base = const_cast<std::uint8_t*>(frame.data());  // sendmsg does not write it
      iov[i].iov_len = frame.size();
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
    }
    const int done = ::sendmmsg(socket_.native_handle(), msgs.data(), static_cast<unsigned>(n), 0);
    const std::size_t accepted = done > 0 ? static_cast<std::size_t>(done) : 0U;
    for (std::size_t i = 0; i < accepted; ++i) {
      ++counters_.frames_sent;
      counters_.bytes_sent += frames[next + i].size();
    }
    next += accepted;
    sent += accepted;
    if (accepted < n) {
      // The OS refused this frame: once more through send(), which knows (and counts) every error
      // and retries after a pending ICMP error; the rest goes on in the next batch.
      sent += send(frames[next]) ? 1U : 0U;
      ++next;
    }
  }
#else
  // No sendmmsg: one send() per frame.
  std::size_t sent = 0;
  for (const auto& frame : frames) sent += send(frame) ? 1U : 0U;
#endif
  return sent;
}

}  // namespace mocaplink::io

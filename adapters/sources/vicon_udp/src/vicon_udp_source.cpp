#include "mocaplink/sources/vicon_udp_source.hpp"

#include <array>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/io/clock.hpp"

namespace mocaplink::sources {

namespace vu = wire::vicon_udp;
using asio::ip::udp;

namespace {

// §4.5: a 64 KiB buffer takes any datagram.
constexpr std::size_t kDatagramBytes = 65536;

vu::StreamConfig stream_config(const ViconUdpOptions& o) {
  return vu::StreamConfig{o.rotation, o.frozen, o.arena_m * 1000.0};
}

}  // namespace

class ViconUdpSource::Receiver {
 public:
  Receiver(ViconUdpSource& owner, FrameSink on_frame, StateSink on_state)
      : owner_(owner),
        on_frame_(std::move(on_frame)),
        on_state_(std::move(on_state)),
        stream_(stream_config(owner.options_)) {}

  /// Binds; run() reports an error.
  void bind() { bind_error_ = try_bind(); }

  std::optional<std::string> try_bind() {
    const auto& o = owner_.options_;
    asio::error_code ec;
    const auto address = asio::ip::make_address(o.bind_host, ec);
    if (ec) return "bad bind address '" + o.bind_host + "': " + ec.message();
    if (!o.from.empty()) from_ = asio::ip::make_address(o.from, ec);
    const udp::endpoint local(address, o.port);
    if (socket_.open(local.protocol(), ec); ec) return "socket: " + ec.message();
    if (socket_.bind(local, ec); ec) {
      return "cannot bind " + o.bind_host + ":" + std::to_string(o.port) + ": " + ec.message();
    }
    owner_.bound_port_ = socket_.local_endpoint(ec).port();
    return std::nullopt;
  }

  void run() {
    if (bind_error_) {
      set_error(*bind_error_);
      if (on_state_) on_state_(SourceState::disconnected, *bind_error_);
      return;
    }
    if (on_state_) {
      on_state_(SourceState::connecting,
                "listening on UDP port " + std::to_string(owner_.bound_port_.load()));
    }
    receive();
    io_.run();
    asio::error_code ignored;
    socket_.close(ignored);
  }

  void stop() { io_.stop(); }

 private:
  void set_error(std::string error) {
    const std::lock_guard lock(owner_.mutex_);
    owner_.last_error_ = std::move(error);
  }

  /// A datagram dropped unread: its reason is the source's last error and last rejection
  /// (bodies, record, the dashboard and the log show it with the count).
  void reject(const std::string& reason) {
    set_error(reason);
    owner_.counters_.last_rejection.set(reason);
  }

  void receive() {
    socket_.async_receive_from(asio::buffer(buffer_), sender_,
                               [this](const asio::error_code& ec, std::size_t n) {
                                 if (ec == asio::error::operation_aborted) return;
                                 if (!ec) on_datagram(n);
                                 receive();  // ICMP errors and the like never stop the loop
                               });
  }

  void on_datagram(std::size_t n) {
    if (from_ && sender_.address() != *from_) {
      // The reason first, then the count: a reader that sees the count sees why.
      reject("datagram from " + sender_.address().to_string() + ", not " + owner_.options_.from +
             " (from=)");
      ++owner_.udp_counters_.foreign;
      ++owner_.counters_.refused;
      return;
    }
    auto out = stream_.on_datagram(std::span<const std::byte>(buffer_.data(), n), io::host_now());
    copy_counters();
    if (!out) {
      reject("malformed datagram at byte " + std::to_string(out.error().offset) + ": " +
             out.error().reason);
      ++owner_.counters_.malformed;
      return;
    }
    if (!live_) {
      live_ = true;
      if (on_state_) {
        on_state_(SourceState::connected, "datagrams of " + std::to_string(n) + " bytes from " +
                                              sender_.address().to_string());
      }
    }
    watch_silence();
    deliver(std::move(out).value());
  }

  void watch_silence() {
    silence_.expires_after(owner_.options_.lost);
    silence_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      deliver(stream_.on_silence(io::host_now()));
      live_ = false;
      if (on_state_) {
        on_state_(SourceState::disconnected,
                  "no datagram for " + std::to_string(owner_.options_.lost.count()) + " ms");
      }
    });
  }

  void deliver(std::optional<core::MocapFrame> frame) {
    if (!frame) return;
    ++owner_.counters_.frames;
    if (on_frame_) on_frame_(std::move(*frame), io::host_now());
  }

  void copy_counters() {
    using S = vu::StreamCounters;
    using U = ViconUdpCounters;
    static constexpr std::array<std::pair<std::uint64_t S::*, std::atomic<std::uint64_t> U::*>, 9>
        kCopied{{{&S::datagrams, &U::datagrams},
                 {&S::late, &U::late},
                 {&S::wraps, &U::wraps},
                 {&S::restarts, &U::restarts},
                 {&S::gaps, &U::gaps},
                 {&S::split_frames, &U::split_frames},
                 {&S::unknown_items, &U::unknown_items},
                 {&S::untracked, &U::untracked},
                 {&S::padded, &U::padded}}};
    for (const auto& [from, to] : kCopied) owner_.udp_counters_.*to = stream_.counters().*from;
  }

  ViconUdpSource& owner_;
  FrameSink on_frame_;
  StateSink on_state_;
  asio::io_context io_;  // first: destroyed after the socket and timer that use it
  udp::socket socket_{io_};
  asio::steady_timer silence_{io_};
  udp::endpoint sender_;
  std::optional<asio::ip::address> from_;
  std::vector<std::byte> buffer_ = std::vector<std::byte>(kDatagramBytes);
  vu::Stream stream_;
  bool live_ = false;
  std::optional<std::string> bind_error_;
};

ViconUdpSource::ViconUdpSource(ViconUdpOptions options, std::string url)
    : options_(std::move(options)), url_(std::move(url)) {}

ViconUdpSource::~ViconUdpSource() {
  stop();
}

void ViconUdpSource::start(FrameSink on_frame, StateSink on_state) {
  if (worker_.running()) return;
  auto receiver = std::make_unique<Receiver>(*this, std::move(on_frame), std::move(on_state));
  receiver->bind();
  worker_.start(std::move(receiver));
}

void ViconUdpSource::stop() {
  worker_.stop();
}

std::string ViconUdpSource::last_error() const {
  const std::lock_guard lock(mutex_);
  return last_error_;
}

}  // namespace mocaplink::sources

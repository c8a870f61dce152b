#include "mocaplink/io/link_stream.hpp"

#include <algorithm>
#include <utility>

#include "mocaplink/io/clock.hpp"

namespace mocaplink::io {

StreamLink::StreamLink(asio::io_context& loop, LinkOptions options, double bytes_per_second)
    : Link(std::move(options)),
      loop_(loop),
      backlog_(options_.max_backlog_bytes),
      bytes_per_second_(bytes_per_second),
      gate_(PosesFirst::Options{.bytes_per_second = bytes_per_second,
                                .max_queue_bytes = options_.max_backlog_bytes}),
      retry_timer_(loop),
      forward_timer_(loop),
      linger_timer_(loop) {}

StreamLink::~StreamLink() {
  retry_timer_.cancel();
  forward_timer_.cancel();
  linger_timer_.cancel();
}

void StreamLink::start(FrameHandler on_frame, StateHandler on_state) {
  set_handlers(std::move(on_frame), std::move(on_state));
  open();
}

void StreamLink::open() {
  if (closing_ || state() == TransportState::closed) return;
  const std::uint64_t generation = ++generation_;
  async_open([this, generation](const std::error_code& error, const std::string& detail) {
    on_opened(generation, error, detail);
  });
}

void StreamLink::on_opened(std::uint64_t generation, const std::error_code& error,
                           const std::string& detail) {
  if (generation != generation_ || closing_ || state() == TransportState::closed) return;
  if (error) {
    if (error == asio::error::connection_refused) ++counters_.refused;
    close_transport();
    set_state(TransportState::down, detail + ": " + error.message());
    retry_timer_.expires_after(next_backoff());
    retry_timer_.async_wait([this](const std::error_code& e) {
      if (!e) open();
    });
    return;
  }
  reset_backoff();
  ++counters_.connects;
  set_state(TransportState::up, detail);
  read();
}

void StreamLink::read() {
  const std::uint64_t generation = generation_;
  async_read_some(read_buffer_, [this, generation](const std::error_code& error, std::size_t n) {
    if (generation != generation_ || state() == TransportState::closed) return;
    if (n > 0) receive_stream(std::span<const std::uint8_t>(read_buffer_.data(), n));
    if (error) {
      if (error != asio::error::eof) ++counters_.receive_errors;
      lose_connection(error == asio::error::eof ? "closed by peer" : error.message());
      return;
    }
    read();
  });
}

bool StreamLink::send(std::span<const std::uint8_t> frame) {
  if (state() != TransportState::up || closing_) {
    ++counters_.dropped_down;
    return false;
  }
  if (!backlog_.append(frame)) {
    ++counters_.dropped_backlog;
    return false;
  }
  gate_.on_own_write(frame.size(), host_now());
  kick_write();
  return true;
}

bool StreamLink::send_forwarded(std::span<const std::uint8_t> frame) {
  if (state() != TransportState::up || closing_) {
    ++counters_.dropped_down;
    ++counters_.forwarded_dropped;
    return false;
  }
  if (!gate_.push(frame, host_now())) {
    ++counters_.forwarded_dropped;
    return false;
  }
  pump_forwarded();
  return true;
}

void StreamLink::pump_forwarded() {
  if (gate_.empty() || state() != TransportState::up || closing_) return;
  if (backlog_.writing() || backlog_.has_pending()) return;  // kick_write calls again when done
  const core::HostTime now = host_now();
  const auto again_in = [this](core::HostTime::duration delay) {
    forward_timer_.expires_after(std::max(delay, core::HostTime::duration{0}));
    forward_timer_.async_wait([this](const std::error_code& e) {
      if (!e) pump_forwarded();
    });
  };
  // What the OS still holds (a TCP send buffer can hold seconds of a slow Wi-Fi's traffic, a
  // tty's buffer a few KiB): a forwarded frame is added only when at most one frame waits there,
  // so that a pose written next is not queued behind ground-station traffic.
  if (const auto unsent = unsent_bytes()) {
    if (*unsent > mavlink::kMaxFrameSize) {
      again_in(kUnsentPoll);
      return;
    }
    gate_.observe_unsent(*unsent, now);  // the OS's word over the model's
  }
  core::HostTime retry_at{};
  const std::uint64_t stale_before = gate_.counters().dropped_stale;
  auto frame = gate_.next(now, retry_at);
  counters_.forwarded_dropped += gate_.counters().dropped_stale - stale_before;
  if (!frame) {
    if (!gate_.empty()) again_in(retry_at - now);
    return;
  }
  if (!backlog_.append(*frame)) {  // only a frame larger than the whole backlog
    ++counters_.forwarded_dropped;
    return;
  }
  ++counters_.forwarded_sent;
  counters_.forwarded_bytes += frame->size();
  kick_write();
}

void StreamLink::kick_write() {
  if (backlog_.writing() || !backlog_.has_pending()) return;
  const std::uint64_t generation = generation_;
  const auto bytes = backlog_.begin_write();
  async_write_all(bytes, [this, generation, size = bytes.size()](const std::error_code& error,
                                                                 std::size_t /*n*/) {
    if (generation != generation_) return;
    if (error) {
      if (state() == TransportState::closed) return;
      ++counters_.send_errors;
      lose_connection(error.message());
      if (closing_) finish_close();
      return;
    }
    counters_.frames_sent += backlog_.finish_write();
    counters_.bytes_sent += size;
    kick_write();
    pump_forwarded();
    if (closing_ && !backlog_.writing()) finish_close();
  });
}

void StreamLink::reconnect_now(const std::string& why) {
  if (closing_ || state() == TransportState::closed) return;
  lose_connection(why, true);
}

void StreamLink::lose_connection(const std::string& why, bool at_once) {
  end_stream();
  close_transport();
  ++generation_;  // ignore completions of the dead connection
  counters_.dropped_down += backlog_.clear();
  counters_.forwarded_dropped += gate_.clear();
  forward_timer_.cancel();
  if (closing_) return;
  set_state(TransportState::down, why);
  if (at_once) {
    retry_timer_.cancel();
    open();
    return;
  }
  retry_timer_.expires_after(next_backoff());
  retry_timer_.async_wait([this](const std::error_code& e) {
    if (!e) open();
  });
}

void StreamLink::close(std::chrono::milliseconds linger) {
  if (closing_ || state() == TransportState::closed) return;
  closing_ = true;
  retry_timer_.cancel();
  if (state() == TransportState::up && backlog_.writing() && linger.count() > 0) {
    // Let the queued frames leave, but never wait longer than `linger`.
    linger_timer_.expires_after(linger);
    linger_timer_.async_wait([this](const std::error_code& e) {
      if (!e) finish_close();
    });
    return;
  }
  finish_close();
}

void StreamLink::finish_close() {
  if (state() == TransportState::closed) return;
  linger_timer_.cancel();
  ++generation_;
  counters_.dropped_down += backlog_.clear();
  counters_.forwarded_dropped += gate_.clear();
  forward_timer_.cancel();
  close_transport();
  release();
  set_state(TransportState::closed, "closed");
}

}  // namespace mocaplink::io

#include "mocaplink/sources/vicon_source.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/sources/reconnect.hpp"
#include "mocaplink/wire/vicon_client_stream.hpp"
#include "mocaplink/wire/vicon_mocap_frame.hpp"

namespace mocaplink::sources {

namespace vw = wire::vicon;
using asio::ip::tcp;
using SteadyClock = std::chrono::steady_clock;

namespace {

// Our requests are a few dozen bytes each; more than this many unwritten means the socket is stuck.
constexpr std::size_t kMaxQueuedWrites = 64;
// §6.3: the SDK waits 1 s for a pulled frame; we ask again after the same time.
constexpr auto kPullRetry = std::chrono::seconds(1);
constexpr auto kDefaultPeriod = std::chrono::milliseconds(10);

}  // namespace

class ViconSource::Session {
 public:
  Session(ViconSource& owner, FrameSink on_frame, StateSink on_state)
      : owner_(owner),
        opts_(owner.options_),
        on_frame_(std::move(on_frame)),
        report_(std::move(on_state)),
        backoff_(opts_.retry) {}

  void run() {
    asio::post(io_, [this] { connect(); });
    io_.run();
    close_socket();
  }

  void stop() { io_.stop(); }

 private:
  void connect() {
    ++generation_;
    if (attempts_++ > 0) ++owner_.counters_.reconnects;
    report_(SourceState::connecting, opts_.target.host + ":" + std::to_string(opts_.target.port));
    const auto gen = generation_;
    connect_timer_.expires_after(opts_.connect_timeout);
    connect_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_ && !greeted_) fail("connect timeout", false);
    });
    resolver_.async_resolve(
        opts_.target.host, std::to_string(opts_.target.port),
        [this, gen](const asio::error_code& ec, const tcp::resolver::results_type& endpoints) {
          if (gen != generation_) return;
          if (ec) return fail("resolve " + opts_.target.host + ": " + ec.message(), false);
          asio::async_connect(socket_, endpoints,
                              [this, gen](const asio::error_code& cec, const tcp::endpoint&) {
                                if (gen != generation_) return;
                                if (cec) return fail("connect: " + cec.message(), false);
                                asio::error_code ignored;
                                socket_.set_option(tcp::no_delay(true), ignored);
                                arm_silence_timer();
                                read_header();
                              });
        });
  }

  // Drops the connection and schedules the next attempt. `malformed`: the peer's bytes were bad.
  void fail(const std::string& reason, bool malformed) {
    if (malformed) ++owner_.counters_.malformed;
    owner_.set_last_error(reason);
    ++generation_;  // every handler of the old connection now ignores its completion
    close_socket();
    stream_.reset();  // no cached item of the old connection can reach a new frame
    last_frame_id_.reset();
    greeted_ = false;
    write_queue_.clear();
    writing_ = false;
    connect_timer_.cancel();
    silence_timer_.cancel();
    pull_timer_.cancel();
    report_(SourceState::disconnected, reason);
    retry_timer_.expires_after(backoff_.next());
    retry_timer_.async_wait([this](const asio::error_code& ec) {
      if (!ec) connect();
    });
  }

  void close_socket() {
    asio::error_code ignored;
    resolver_.cancel();
    if (socket_.is_open()) {
      socket_.shutdown(tcp::socket::shutdown_both, ignored);
      socket_.close(ignored);
    }
  }

  void arm_silence_timer() {
    const auto gen = generation_;
    silence_timer_.expires_after(opts_.silence_timeout);
    silence_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (ec || gen != generation_) return;
      ++owner_.vicon_counters_.timeouts;
      fail("no data from the server for " + std::to_string(opts_.silence_timeout.count()) + " ms",
           false);
    });
  }

  void read_header() {
    const auto gen = generation_;
    asio::async_read(socket_, asio::buffer(header_),
                     [this, gen](const asio::error_code& ec, std::size_t n) {
                       if (gen != generation_) return;
                       if (ec) return read_failed(ec, n, header_.size());
                       auto length = vw::parse_packet_header(header_, opts_.max_body_bytes);
                       if (!length) return fail(length.error().reason, true);
                       body_.resize(length.value());
                       read_body();
                     });
  }

  void read_body() {
    const auto gen = generation_;
    asio::async_read(socket_, asio::buffer(body_),
                     [this, gen](const asio::error_code& ec, std::size_t n) {
                       if (gen != generation_) return;
                       if (ec)
                         return read_failed(ec, header_.size() + n, header_.size() + body_.size());
                       ++owner_.vicon_counters_.packets;
                       owner_.vicon_counters_.bytes += body_.size() + header_.size();
                       arm_silence_timer();
                       if (on_packet()) read_header();
                     });
  }

  // A read ended early. Bytes of a packet already received make it a truncated (malformed)
  // packet; a close between packets is an ordinary disconnect.
  void read_failed(const asio::error_code& ec, std::size_t have, std::size_t want) {
    if (have > 0 && have < want) {
      return fail("connection closed in the middle of a packet (" + std::to_string(have) + " of " +
                      std::to_string(want) + " bytes): " + ec.message(),
                  true);
    }
    fail("read: " + ec.message(), false);
  }

  // Returns false when the connection was dropped.
  bool on_packet() {
    if (!greeted_) return on_greeting();
    auto outcome = stream_.apply(body_);
    if (!outcome) {
      fail("malformed packet at byte " + std::to_string(outcome.error().offset) + ": " +
               outcome.error().reason,
           true);
      return false;
    }
    const vw::PacketOutcome& out = outcome.value();
    owner_.vicon_counters_.unknown_items += out.unknown_items;
    owner_.vicon_counters_.keep_alives += out.keep_alives;
    if (!out.frame_dropped_reason.empty()) {
      ++owner_.vicon_counters_.frames_without_id;
      owner_.set_last_error(out.frame_dropped_reason);
    }
    if (!out.frame) return true;
    on_frame_packet(*out.frame);
    return true;
  }

  bool on_greeting() {
    auto offered = vw::parse_greeting(body_);
    if (!offered) {
      fail("bad greeting: " + offered.error().reason, true);
      return false;
    }
    greeted_ = true;
    connect_timer_.cancel();
    backoff_.reset();
    ++owner_.vicon_counters_.connections;
    const vw::ObjectEnums request = vw::client_request(offered.value());
    send(packet_of(request));
    std::string detail = std::string("mode ") + vw::to_string(opts_.target.mode);
    if (std::find(request.types.begin(), request.types.end(),
                  vw::to_u32(vw::ItemType::global_segments)) == request.types.end()) {
      detail += "; server offers no GlobalSegments: every body will be untracked";
    }
    switch (opts_.target.mode) {
      case vw::StreamMode::server_push:
        send(packet_of(vw::RequestFrame{true}));
        break;
      case vw::StreamMode::client_prefetch:
        send(packet_of(vw::RequestNextFrame{1}));
        break;
      case vw::StreamMode::client_pull:
        pull_now();
        break;
    }
    report_(SourceState::connected, detail);
    return true;
  }

  void on_frame_packet(const vw::DecodedFrame& decoded) {
    if (decoded.frame_period_ticks) {
      period_ = std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(
          static_cast<double>(*decoded.frame_period_ticks) / vw::kStreamClockHz));
    }
    switch (opts_.target.mode) {
      case vw::StreamMode::server_push:
        break;
      case vw::StreamMode::client_prefetch:
        send(packet_of(vw::RequestNextFrame{1}));
        break;
      case vw::StreamMode::client_pull:
        // One request per frame period; a nonsense period from the server (hours) must not stall
        // the stream, so never wait longer than the retry interval.
        schedule_pull(last_pull_ + std::min<SteadyClock::duration>(period_, kPullRetry));
        break;
    }
    if (last_frame_id_ && *last_frame_id_ == decoded.frame_id) {
      ++owner_.vicon_counters_.repeated_frames;
      return;
    }
    last_frame_id_ = decoded.frame_id;
    vw::MappedFrame mapped = vw::to_mocap_frame(decoded);
    owner_.vicon_counters_.invalid_poses += mapped.invalid_poses;
    ++owner_.counters_.frames;
    if (on_frame_) on_frame_(std::move(mapped.frame), io::host_now());
  }

  void pull_now() {
    last_pull_ = SteadyClock::now();
    send(packet_of(vw::RequestFrame{false}));
    schedule_pull(last_pull_ + kPullRetry);  // ask again if no answer comes
  }

  void schedule_pull(SteadyClock::time_point when) {
    const auto gen = generation_;
    pull_timer_.expires_at(when);
    pull_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_) pull_now();
    });
  }

  template <vw::Item T>
  static std::vector<std::byte> packet_of(const T& item) {
    vw::PacketBuilder b;
    b.add(item);
    return b.finish();
  }

  void send(std::vector<std::byte> packet) {
    if (write_queue_.size() >= kMaxQueuedWrites) {
      return fail("server is not reading our requests", false);
    }
    write_queue_.push_back(std::move(packet));
    if (!writing_) write_next();
  }

  void write_next() {
    if (write_queue_.empty()) {
      writing_ = false;
      return;
    }
    writing_ = true;
    const auto gen = generation_;
    asio::async_write(socket_, asio::buffer(write_queue_.front()),
                      [this, gen](const asio::error_code& ec, std::size_t) {
                        if (gen != generation_) return;
                        if (ec) return fail("write: " + ec.message(), false);
                        write_queue_.pop_front();
                        write_next();
                      });
  }

  ViconSource& owner_;
  const ViconSourceOptions& opts_;
  FrameSink on_frame_;
  StateReporter report_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  tcp::resolver resolver_{io_};
  tcp::socket socket_{io_};
  asio::steady_timer connect_timer_{io_};
  asio::steady_timer silence_timer_{io_};
  asio::steady_timer retry_timer_{io_};
  asio::steady_timer pull_timer_{io_};
  std::array<std::byte, vw::kPacketHeaderBytes> header_{};
  std::vector<std::byte> body_;
  std::deque<std::vector<std::byte>> write_queue_;
  bool writing_ = false;
  vw::ClientStream stream_;
  bool greeted_ = false;
  std::uint64_t generation_ = 0;
  std::uint64_t attempts_ = 0;
  core::RetrySchedule backoff_;
  std::optional<std::uint32_t> last_frame_id_;
  SteadyClock::duration period_ = kDefaultPeriod;
  SteadyClock::time_point last_pull_{};
};

ViconSource::ViconSource(ViconSourceOptions options, std::string url)
    : options_(std::move(options)), url_(std::move(url)) {}

ViconSource::~ViconSource() = default;  // session_ (declared last) stops and joins first

void ViconSource::start(FrameSink on_frame, StateSink on_state) {
  session_.start_once(*this, std::move(on_frame), std::move(on_state));
}

void ViconSource::stop() {
  session_.stop();
}

}  // namespace mocaplink::sources

#include "mocaplink/sources/qtm_source.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/sources/reconnect.hpp"
#include "mocaplink/wire/qtm_frame.hpp"
#include "mocaplink/wire/qtm_parameters.hpp"

namespace mocaplink::sources {

namespace wq = wire::qtm;
using asio::ip::tcp;
using asio::ip::udp;

namespace {

constexpr std::size_t kMaxQueuedCommands = 32;
constexpr std::size_t kMaxDatagram = 65536;
// UDP frames arriving this many frame numbers late are reordered ones; further back is a new
// measurement (QTM restarts its frame numbers), which is accepted.
constexpr std::uint32_t kReorderWindow = 1000;

std::string minor_text(int minor) {
  return "1." + std::to_string(minor);
}

}  // namespace

class QtmSource::Session {
 public:
  Session(QtmSource& owner, FrameSink on_frame, StateSink on_state)
      : owner_(owner),
        opts_(owner.options_),
        on_frame_(std::move(on_frame)),
        report_(std::move(on_state)),
        backoff_(opts_.retry) {}

  void run() {
    asio::post(io_, [this] { connect(); });
    io_.run();
    drop_sockets();
  }

  void stop() { io_.stop(); }

 private:
  enum class Phase { welcome, version, ready };

  std::string target_text() const {
    return opts_.target.host + ":" + std::to_string(opts_.target.port);
  }

  void connect() {
    const auto gen = ++generation_;
    if (attempts_++ > 0) ++owner_.counters_.reconnects;
    report_(SourceState::connecting, target_text());
    connect_timer_.expires_after(opts_.connect_timeout);
    connect_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_ && phase_ != Phase::ready) {
        drop("no protocol version agreed within " + std::to_string(opts_.connect_timeout.count()) +
                 " ms",
             false);
      }
    });
    resolver_.async_resolve(
        opts_.target.host, std::to_string(opts_.target.port),
        [this, gen](const asio::error_code& ec, const tcp::resolver::results_type& results) {
          if (gen != generation_) return;
          if (ec) return drop("resolve " + opts_.target.host + ": " + ec.message(), false);
          asio::async_connect(socket_, results,
                              [this, gen](const asio::error_code& cec, const tcp::endpoint&) {
                                if (gen != generation_) return;
                                if (cec) return drop("connect: " + cec.message(), false);
                                asio::error_code ignored;
                                socket_.set_option(tcp::no_delay(true), ignored);
                                last_packet_ = std::chrono::steady_clock::now();
                                watch_silence();
                                read_header();
                              });
        });
  }

  // Ends the connection (counting `malformed` when the peer's bytes were at fault) and schedules
  // the next attempt. Everything learnt from the old connection is forgotten here.
  void drop(const std::string& reason, bool malformed) {
    if (malformed) ++owner_.counters_.malformed;
    owner_.set_last_error(reason);
    ++generation_;
    drop_sockets();
    phase_ = Phase::welcome;
    bodies_.reset();
    frequency_hz_.reset();
    parameters_pending_ = false;
    streaming_ = false;
    last_frame_.reset();
    probe_sent_ = false;
    commands_.clear();
    writing_ = false;
    for (auto* t : {&connect_timer_, &silence_timer_, &parameters_timer_}) t->cancel();
    report_(SourceState::disconnected, reason);
    retry_timer_.expires_after(backoff_.next());
    retry_timer_.async_wait([this](const asio::error_code& ec) {
      if (!ec) connect();
    });
  }

  void drop_sockets() {
    asio::error_code ignored;
    resolver_.cancel();
    if (socket_.is_open()) {
      socket_.shutdown(tcp::socket::shutdown_both, ignored);
      socket_.close(ignored);
    }
    if (udp_.is_open()) udp_.close(ignored);
  }

  // Every silence_timeout: nothing heard since the last look → probe once, then give up.
  void watch_silence() {
    const auto gen = generation_;
    silence_timer_.expires_after(opts_.silence_timeout);
    silence_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (ec || gen != generation_) return;
      if (std::chrono::steady_clock::now() - last_packet_ >= opts_.silence_timeout) {
        if (probe_sent_) {
          ++owner_.qtm_counters_.timeouts;
          return drop("no answer from the server for " +
                          std::to_string(2 * opts_.silence_timeout.count()) + " ms",
                      false);
        }
        if (phase_ == Phase::ready) {
          probe_sent_ = true;
          command("ByteOrder");
        }
      }
      watch_silence();
    });
  }

  void heard(std::size_t bytes) {
    ++owner_.qtm_counters_.packets;
    owner_.qtm_counters_.bytes += bytes;
    last_packet_ = std::chrono::steady_clock::now();
    probe_sent_ = false;
  }

  void read_header() {
    const auto gen = generation_;
    asio::async_read(socket_, asio::buffer(header_),
                     [this, gen](const asio::error_code& ec, std::size_t n) {
                       if (gen != generation_) return;
                       if (ec) return read_ended(ec, n, header_.size());
                       auto header = wq::parse_header(header_, opts_.max_packet_bytes);
                       if (!header) return drop(header.error().reason, true);
                       type_ = header.value().type;
                       payload_.resize(header.value().size - wq::kHeaderBytes);
                       read_payload();
                     });
  }

  void read_payload() {
    const auto gen = generation_;
    asio::async_read(
        socket_, asio::buffer(payload_), [this, gen](const asio::error_code& ec, std::size_t n) {
          if (gen != generation_) return;
          if (ec) {
            return read_ended(ec, header_.size() + n, header_.size() + payload_.size());
          }
          heard(header_.size() + payload_.size());
          on_packet(type_, payload_);
          if (gen == generation_) read_header();
        });
  }

  void read_ended(const asio::error_code& ec, std::size_t have, std::size_t want) {
    if (have > 0 && have < want) {
      return drop("connection closed inside a packet (" + std::to_string(have) + " of " +
                      std::to_string(want) + " bytes): " + ec.message(),
                  true);
    }
    drop("read: " + ec.message(), false);
  }

  void on_packet(std::uint32_t type, std::span<const std::byte> payload) {
    using T = wq::PacketType;
    const std::string text =
        type == static_cast<std::uint32_t>(T::data) ? "" : wq::text_of(payload);
    if (phase_ == Phase::welcome) {
      if (type == static_cast<std::uint32_t>(T::command) && text.starts_with(wq::kWelcome)) {
        phase_ = Phase::version;
        minor_ = opts_.target.newest_minor;
        return command("Version " + minor_text(minor_));
      }
      if (type == static_cast<std::uint32_t>(T::error)) {
        ++owner_.qtm_counters_.server_errors;
        return drop("server: " + text, false);
      }
      return drop("not a QTM RT server (no welcome)", true);
    }
    switch (static_cast<T>(type)) {
      case T::event:
        return on_event(payload);
      case T::error:
        ++owner_.qtm_counters_.server_errors;
        owner_.set_last_error("server: " + text);
        if (phase_ == Phase::version) return next_version();
        if (parameters_pending_) parameters_unavailable();
        return;
      case T::command:
        if (phase_ == Phase::version) {
          if (text.starts_with("Version set to")) return version_set();
          return next_version();
        }
        if (parameters_pending_ && text.starts_with("Parameters not available")) {
          owner_.set_last_error("server: " + text);
          parameters_unavailable();
        }
        return;
      case T::xml:
        if (parameters_pending_) on_parameters(text);
        return;
      case T::data:
        if (phase_ == Phase::ready) on_data(payload);
        return;
      case T::no_more_data:
        ++owner_.qtm_counters_.no_more_data;
        return;
      default:
        return;  // C3D/QTM files, discovery: not asked for
    }
  }

  void next_version() {
    if (--minor_ < wq::kOldestMinor) {
      return drop("the server sets none of the protocol versions " +
                      minor_text(opts_.target.newest_minor) + " down to " +
                      minor_text(wq::kOldestMinor),
                  false);
    }
    command("Version " + minor_text(minor_));
  }

  void version_set() {
    phase_ = Phase::ready;
    connect_timer_.cancel();
    backoff_.reset();
    ++owner_.qtm_counters_.connections;
    std::string detail = "protocol " + minor_text(minor_) + ", " +
                         std::string(wq::to_string(opts_.target.component));
    if (opts_.target.udp_port) {
      if (auto err = open_udp(); !err.empty()) return drop(err, false);
      detail += " over UDP port " + std::to_string(udp_.local_endpoint().port());
    } else {
      detail += " over TCP";
    }
    connected_detail_ = detail;
    request_parameters();
  }

  std::string open_udp() {
    asio::error_code ec;
    const tcp::endpoint local = socket_.local_endpoint(ec);
    if (ec) return "local address: " + ec.message();
    const udp::endpoint bind_to(local.address(), *opts_.target.udp_port);
    if (udp_.open(bind_to.protocol(), ec); ec) return "UDP socket: " + ec.message();
    if (udp_.bind(bind_to, ec); ec) {
      return "cannot bind UDP port " + std::to_string(*opts_.target.udp_port) + ": " + ec.message();
    }
    datagram_.resize(kMaxDatagram);
    receive_datagram();
    return {};
  }

  void receive_datagram() {
    const auto gen = generation_;
    udp_.async_receive_from(
        asio::buffer(datagram_), sender_, [this, gen](const asio::error_code& ec, std::size_t n) {
          if (gen != generation_) return;
          if (ec) return drop("UDP receive: " + ec.message(), false);
          asio::error_code peer_ec;
          // Only the server's datagrams: anything else on the port is not ours to parse.
          if (sender_.address() == socket_.remote_endpoint(peer_ec).address() && !peer_ec) {
            heard(n);
            auto packet = wq::parse_packet(std::span(datagram_).first(n), opts_.max_packet_bytes);
            if (!packet) {
              count_malformed("UDP datagram: " + packet.error().reason);
            } else if (packet.value().type == static_cast<std::uint32_t>(wq::PacketType::data)) {
              on_data(packet.value().payload, true);
            }
          }
          receive_datagram();
        });
  }

  void count_malformed(const std::string& reason) {
    ++owner_.counters_.malformed;
    owner_.set_last_error(reason);
  }

  void on_event(std::span<const std::byte> payload) {
    ++owner_.qtm_counters_.events;
    if (payload.empty()) return count_malformed("event packet without an event number");
    const auto event = static_cast<std::uint8_t>(payload[0]);
    if (event == static_cast<std::uint8_t>(wq::Event::rt_from_file_started)) {
      owner_.set_last_error("QTM is playing a file (RT from file), not live data");
    }
    if (wq::invalidates_parameters(event) && phase_ == Phase::ready) {
      bodies_.reset();
      request_parameters();
    }
  }

  void request_parameters() {
    if (parameters_pending_) return;
    parameters_pending_ = true;
    parameters_timer_.cancel();
    command("GetParameters General 6D");
  }

  void parameters_unavailable() {
    parameters_pending_ = false;
    const auto gen = generation_;
    parameters_timer_.expires_after(opts_.parameters_retry);
    parameters_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_ && !bodies_) request_parameters();
    });
  }

  void on_parameters(const std::string& xml) {
    auto parsed = wq::parse_parameters(xml);
    if (!parsed) {
      count_malformed("parameters XML at byte " + std::to_string(parsed.error().offset) + ": " +
                      parsed.error().reason);
      return parameters_unavailable();
    }
    const wq::Parameters& p = parsed.value();
    if (!p.has_6d) {
      owner_.set_last_error("parameters without a The_6D section");
      return parameters_unavailable();
    }
    parameters_pending_ = false;
    ++owner_.qtm_counters_.parameter_reads;
    bodies_ = p.bodies;
    if (p.frequency_hz) frequency_hz_ = p.frequency_hz;
    ambiguous_.clear();
    std::string warnings;
    const auto warn = [&](const std::string& text) {
      owner_.set_last_error(text);
      warnings += "; " + text;
    };
    std::set<std::string> seen;
    for (const auto& b : p.bodies) {
      if (!seen.insert(b.name).second) ambiguous_.insert(b.name);
      if (!b.global) warn("body " + b.name + " is not in global coordinates (Data_origin)");
    }
    if (!ambiguous_.empty()) {
      warn("duplicate body name " + *ambiguous_.begin() + " in QTM: those bodies stay untracked");
    }
    // Connected once the first body list is in, with what is wrong in it.
    report_(SourceState::connected,
            connected_detail_ + ", " + std::to_string(p.bodies.size()) + " bodies" + warnings);
    if (!streaming_) {
      streaming_ = true;
      std::string cmd = "StreamFrames AllFrames ";
      if (opts_.target.udp_port) cmd += "UDP:" + std::to_string(udp_.local_endpoint().port()) + " ";
      command(cmd + std::string(wq::to_string(opts_.target.component)));
    }
  }

  void on_data(std::span<const std::byte> payload, bool via_udp = false) {
    auto data = wq::parse_data(payload);
    if (!data) {
      return count_malformed("data packet at byte " + std::to_string(data.error().offset) + ": " +
                             data.error().reason);
    }
    if (data.value().six_dof.empty()) return;  // another component in its own packet (UDP split)
    if (!bodies_) {
      ++owner_.qtm_counters_.frames_without_names;
      return;
    }
    auto mapped = wq::to_mocap_frame(data.value(), opts_.target.component, *bodies_, frequency_hz_);
    if (!mapped) {
      ++owner_.qtm_counters_.body_count_changes;
      owner_.set_last_error(mapped.error().reason + "; reading the body list again");
      bodies_.reset();
      return request_parameters();
    }
    const std::uint32_t frame_number = data.value().frame_number;
    if (last_frame_ &&
        (frame_number == *last_frame_ || (via_udp && frame_number < *last_frame_ &&
                                          *last_frame_ - frame_number < kReorderWindow))) {
      ++owner_.qtm_counters_.repeated_frames;
      return;
    }
    last_frame_ = frame_number;
    wq::MappedFrame& out = mapped.value();
    owner_.qtm_counters_.invalid_poses += out.invalid_poses;
    for (auto& body : out.frame.bodies) {
      if (ambiguous_.count(body.name) != 0) body.tracked = false;
    }
    ++owner_.counters_.frames;
    if (on_frame_) on_frame_(std::move(out.frame), io::host_now());
  }

  void command(const std::string& text) {
    if (commands_.size() >= kMaxQueuedCommands) {
      return drop("the server is not reading our commands", false);
    }
    commands_.push_back(wq::encode_text(wq::PacketType::command, text));
    if (!writing_) write_front();
  }

  void write_front() {
    writing_ = !commands_.empty();
    if (!writing_) return;
    const auto gen = generation_;
    asio::async_write(socket_, asio::buffer(commands_.front()),
                      [this, gen](const asio::error_code& ec, std::size_t) {
                        if (gen != generation_) return;
                        if (ec) return drop("write: " + ec.message(), false);
                        commands_.pop_front();
                        write_front();
                      });
  }

  QtmSource& owner_;
  const QtmSourceOptions& opts_;
  FrameSink on_frame_;
  StateReporter report_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  tcp::resolver resolver_{io_};
  tcp::socket socket_{io_};
  udp::socket udp_{io_};
  udp::endpoint sender_;
  asio::steady_timer connect_timer_{io_};
  asio::steady_timer silence_timer_{io_};
  asio::steady_timer retry_timer_{io_};
  asio::steady_timer parameters_timer_{io_};
  std::array<std::byte, wq::kHeaderBytes> header_{};
  std::uint32_t type_ = 0;
  std::vector<std::byte> payload_;
  std::vector<std::byte> datagram_;
  std::deque<std::vector<std::byte>> commands_;
  bool writing_ = false;
  Phase phase_ = Phase::welcome;
  int minor_ = wq::kNewestMinor;
  std::optional<std::vector<wq::BodyParameters>> bodies_;
  std::optional<double> frequency_hz_;
  std::set<std::string> ambiguous_;
  std::string connected_detail_;
  bool parameters_pending_ = false;
  bool streaming_ = false;
  bool probe_sent_ = false;
  std::optional<std::uint32_t> last_frame_;
  std::chrono::steady_clock::time_point last_packet_{};
  std::uint64_t generation_ = 0;
  std::uint64_t attempts_ = 0;
  core::RetrySchedule backoff_;
};

QtmSource::QtmSource(QtmSourceOptions options, std::string url)
    : options_(std::move(options)), url_(std::move(url)) {}

QtmSource::~QtmSource() = default;  // session_ (declared last) stops and joins first

void QtmSource::start(FrameSink on_frame, StateSink on_state) {
  session_.start_once(*this, std::move(on_frame), std::move(on_state));
}

void QtmSource::stop() {
  session_.stop();
}

}  // namespace mocaplink::sources

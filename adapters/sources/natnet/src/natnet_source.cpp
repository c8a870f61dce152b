#include "mocaplink/sources/natnet_source.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/sources/reconnect.hpp"
#include "mocaplink/wire/natnet_mocap_frame.hpp"

namespace mocaplink::sources {

namespace nn = wire::natnet;
using asio::ip::udp;
using SteadyClock = std::chrono::steady_clock;

namespace {

// Frame numbers this far below the last one mean the server restarted its count, not a repeat.
constexpr std::int64_t kRestartJump = 1000;
// Least time between two re-reads of the server info: a lost reply is asked for again this soon.
constexpr auto kRevalidateEvery = std::chrono::milliseconds(250);

std::string ipv4_text(const std::array<std::uint8_t, 4>& a) {
  return std::to_string(a[0]) + "." + std::to_string(a[1]) + "." + std::to_string(a[2]) + "." +
         std::to_string(a[3]);
}

}  // namespace

class NatnetSource::Session {
 public:
  Session(NatnetSource& owner, FrameSink on_frame, StateSink on_state)
      : owner_(owner),
        opts_(owner.options_),
        on_frame_(std::move(on_frame)),
        state_(std::move(on_state)),
        backoff_(opts_.retry) {}

  void run() {
    asio::post(io_, [this] { connect(); });
    io_.run();
    // Tell a unicast server we are gone (§1.2 step 5); harmless for multicast.
    if (server_ && cmd_.socket.is_open()) {
      asio::error_code ignored;
      cmd_.socket.send_to(asio::buffer(nn::encode_empty(nn::MessageId::disconnect)), *server_, 0,
                          ignored);
    }
    close_sockets();
  }

  void stop() { io_.stop(); }

 private:
  struct Receiver {
    explicit Receiver(asio::io_context& io) : socket(io) {}
    udp::socket socket;
    udp::endpoint from;
    std::vector<std::byte> buffer = std::vector<std::byte>(nn::kMaxDatagramBytes);
  };

  // Where a datagram was read: the data socket, or the command socket from the server's command
  // port or its data port.
  enum class Origin { data_socket, command_port, data_port };

  udp::endpoint local_endpoint(std::uint16_t port) const {
    asio::error_code ec;
    const auto address = opts_.target.local.empty()
                             ? asio::ip::address_v4::any()
                             : asio::ip::make_address_v4(opts_.target.local, ec);
    return {address, port};
  }

  void connect() {
    ++generation_;
    if (attempts_++ > 0) ++owner_.counters_.reconnects;
    state_(SourceState::connecting,
           opts_.target.host + ":" + std::to_string(opts_.target.command_port));
    const auto gen = generation_;
    silence_timer_.expires_after(opts_.silence_timeout);
    silence_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_ && !info_) fail("no server info (is Motive streaming?)", false);
    });
    resolver_.async_resolve(
        udp::v4(), opts_.target.host, std::to_string(opts_.target.command_port),
        [this, gen](const asio::error_code& ec, const udp::resolver::results_type& results) {
          if (gen != generation_) return;
          if (ec || results.empty()) {
            return fail("resolve " + opts_.target.host + ": " + ec.message(), false);
          }
          server_ = results.begin()->endpoint();
          server_data_port_ = opts_.target.data_port.value_or(nn::kDefaultDataPort);
          asio::error_code oec;
          cmd_.socket.open(udp::v4(), oec);
          if (!oec) cmd_.socket.bind(local_endpoint(0), oec);
          if (oec)
            return fail("command socket on " + opts_.target.local + ": " + oec.message(), false);
          receive(cmd_);
          send_connect();
        });
  }

  void send_connect() {
    nn::ConnectRequest req;
    req.sender.name = "mocaplink";
    req.sender.natnet_version = {4, 1, 0, 0};
    send(nn::encode_connect(req));
    const auto gen = generation_;
    connect_timer_.expires_after(opts_.connect_retry);
    connect_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_ && !info_) send_connect();
    });
  }

  void send(const std::vector<std::byte>& packet) {
    if (!server_ || !cmd_.socket.is_open()) return;
    asio::error_code ignored;
    cmd_.socket.send_to(asio::buffer(packet), *server_, 0, ignored);
  }

  void receive(Receiver& r) {
    const auto gen = generation_;
    r.socket.async_receive_from(asio::buffer(r.buffer), r.from,
                                [this, gen, &r](const asio::error_code& ec, std::size_t n) {
                                  if (gen != generation_) return;
                                  if (ec) {
                                    if (ec == asio::error::operation_aborted) return;
                                    // ICMP port unreachable from a server not (yet) listening: keep
                                    // trying.
                                    return receive(r);
                                  }
                                  const auto bytes = std::span<const std::byte>(r.buffer.data(), n);
                                  if (&r != &cmd_) {
                                    on_datagram(bytes, Origin::data_socket);
                                  } else if (const auto origin = command_socket_origin(r.from)) {
                                    on_datagram(bytes, *origin);
                                  } else {
                                    // The command socket hears only the server: its port may have
                                    // belonged to another program's client a moment ago, whose
                                    // unicast server still streams to it.
                                    ++owner_.natnet_counters_.foreign_datagrams;
                                  }
                                  if (gen == generation_) receive(r);
                                });
  }

  // Where a datagram on the command socket comes from, if from the server: its command port
  // (replies) or its data port (Motive's unicast frames, docs/sources.md "Where unicast frames
  // come from"); any other sender is foreign.
  std::optional<Origin> command_socket_origin(const udp::endpoint& from) const {
    if (!server_) return std::nullopt;
    if (from == *server_) return Origin::command_port;
    if (from.address() == server_->address() && from.port() == server_data_port_) {
      return Origin::data_port;
    }
    return std::nullopt;
  }

  void malformed(const std::string& what, const wire::ParseError& e) {
    ++owner_.counters_.malformed;
    owner_.last_error_.set("malformed " + what + " at byte " + std::to_string(e.offset) + ": " +
                           e.reason);
  }

  void on_datagram(std::span<const std::byte> bytes, Origin origin) {
    ++owner_.natnet_counters_.packets;
    auto packet = nn::split_packet(bytes);
    if (!packet) return malformed("datagram", packet.error());
    if (packet.value().trailing_bytes > 0) ++owner_.natnet_counters_.trailing_bytes;
    const auto payload = packet.value().payload;
    switch (static_cast<nn::MessageId>(packet.value().id)) {
      case nn::MessageId::server_info:
        return on_server_info(payload);
      case nn::MessageId::model_def:
        return on_model_definitions(payload);
      case nn::MessageId::frame_of_data:
        // Motive sends unicast frames from its data port; OptiTrack's library drops frames from
        // the command port. mocaplink still reads them (the endpoint is the server's own, that
        // answers the connect), counted.
        if (origin == Origin::command_port) ++owner_.natnet_counters_.frames_from_command_port;
        return on_frame(payload);
      case nn::MessageId::response:
        return on_response(payload);
      case nn::MessageId::disconnect_by_timeout:
        // Motive ends a unicast session it heard no keep-alive for (about 10 s): start again.
        ++owner_.natnet_counters_.disconnects_by_server;
        return fail(
            "Motive ended the unicast session (NAT_DISCONNECTBYTIMEOUT: no keep-alive heard)",
            false);
      default:
        return;  // message strings, echoes: nothing we asked for
    }
  }

  // The reply to our "Bitstream" query (NatNet 4 servers, §1.2): "Bitstream,X.Y[.Z]". Result
  // codes and other strings are not ours to read.
  void on_response(std::span<const std::byte> payload) {
    if (!info_ || payload.size() == 4) return;
    // With or without a NUL: Motive seems to send none (nn::encode_response_text).
    const std::string text = nn::parse_response_text(payload);
    if (text.rfind("Bitstream,", 0) != 0) return;
    unsigned major = 0;
    unsigned minor = 0;
    if (std::sscanf(text.c_str() + 10, "%u.%u", &major, &minor) != 2 || major > 255 ||
        minor > 255) {
      return;
    }
    const nn::Version v{static_cast<std::uint8_t>(major), static_cast<std::uint8_t>(minor)};
    if (v == info_->version()) return;
    if (!nn::supported(v)) {
      return fail(
          "Motive streams NatNet bitstream " + v.to_string() + "; mocaplink reads 2.5 up to 4.x",
          false);
    }
    info_->sender.natnet_version = {v.major, v.minor, 0, 0};
    change_version();
  }

  // The bitstream changed under a live session: frames of the new version are not read with the
  // old model table, so the table is dropped and asked for again at once.
  void change_version() {
    ++owner_.natnet_counters_.bitstream_changes;
    table_.reset();
    request_models(true);
  }

  void on_server_info(std::span<const std::byte> payload) {
    auto parsed = nn::parse_server_info(payload);
    if (!parsed) return malformed("server info", parsed.error());
    const nn::ServerInfo& info = parsed.value();
    const nn::Version v = info.version();
    if (!nn::supported(v)) {
      return fail(
          "Motive streams NatNet bitstream " + v.to_string() + "; mocaplink reads 2.5 up to 4.x",
          false);
    }
    const bool first = !info_;
    const bool changed = info_ && info_->version() != v;
    info_ = info;
    if (changed) change_version();
    if (!first) return;
    connect_timer_.cancel();
    backoff_.reset();
    ++owner_.natnet_counters_.connections;
    multicast_ = opts_.target.transport == NatnetTransport::automatic
                     ? (!info.has_connection_info || info.multicast)
                     : opts_.target.transport == NatnetTransport::multicast;
    const std::uint16_t data_port = opts_.target.data_port.value_or(
        info.has_connection_info ? info.data_port : nn::kDefaultDataPort);
    server_data_port_ = data_port;
    const std::string group = opts_.target.multicast_group.value_or(
        ipv4_text(info.has_connection_info ? info.multicast_group : nn::kDefaultMulticastGroup));
    if (auto err = open_data_socket(data_port, group)) return fail(*err, false);
    detail_ = "NatNet " + v.to_string() + " from " + info.sender.name + ", " +
              (multicast_ ? "multicast " + group + ":" + std::to_string(data_port)
                          : std::string("unicast"));
    if (!multicast_) keep_alive_tick();
    request_models(true);
    arm_silence_timer();
  }

  // Multicast: the data socket must work. Unicast: frames come to the command socket as well, so
  // a data port another program holds is not fatal.
  std::optional<std::string> open_data_socket(std::uint16_t port, const std::string& group) {
    asio::error_code ec;
    data_.socket.open(udp::v4(), ec);
    if (!ec) data_.socket.set_option(udp::socket::reuse_address(true), ec);
    if (!ec) {
      // Multicast datagrams are delivered to sockets bound to the wildcard (or group) address;
      // the interface is chosen by the join.
      data_.socket.bind(
          multicast_ ? udp::endpoint(asio::ip::address_v4::any(), port) : local_endpoint(port), ec);
    }
    if (!ec && multicast_) {
      const auto g = asio::ip::make_address_v4(group, ec);
      if (!ec) {
        data_.socket.set_option(
            asio::ip::multicast::join_group(g, local_endpoint(0).address().to_v4()), ec);
      }
      if (ec) {
        return "cannot join " + group + " on " +
               (opts_.target.local.empty() ? std::string("the default interface")
                                           : opts_.target.local) +
               ": " + ec.message() + " (set ?local= to the interface facing Motive)";
      }
    }
    if (ec) {
      asio::error_code ignored;
      data_.socket.close(ignored);
      if (multicast_) return "data port " + std::to_string(port) + ": " + ec.message();
      owner_.last_error_.set("unicast data port " + std::to_string(port) + ": " + ec.message() +
                             " (frames are read on the command socket)");
      return std::nullopt;
    }
    receive(data_);
    return std::nullopt;
  }

  void request_models(bool now) {
    const auto t = SteadyClock::now();
    if (!now && t - last_model_request_ < opts_.model_retry) return;
    last_model_request_ = t;
    ++owner_.natnet_counters_.model_requests;
    send(nn::encode_empty(nn::MessageId::request_model_def));
  }

  void on_model_definitions(std::span<const std::byte> payload) {
    if (!info_) return;
    auto defs = nn::parse_model_definitions(payload, info_->version());
    if (!defs) {
      revalidate();  // written in another bitstream (4.1 → 4.2 changes only these)?
      return malformed("model definitions", defs.error());
    }
    table_ = nn::body_table(defs.value());
    ++owner_.natnet_counters_.model_reloads;
    if (!table_->ambiguous.empty()) {
      owner_.last_error_.set("rigid-body name \"" + *table_->ambiguous.begin() +
                             "\" is used by two ids in Motive: its bodies are ignored");
    }
    state_(SourceState::connected, detail_);
  }

  void on_frame(std::span<const std::byte> payload) {
    if (!info_) return;
    auto parsed = nn::parse_frame(payload, info_->version());
    if (!parsed) {
      // Frames that stop decoding may be another bitstream (asked for by this client's host, or
      // a server that changed it without the flag): ask again now, not after silence_timeout.
      revalidate();
      return malformed("frame", parsed.error());
    }
    const nn::FrameOfData& f = parsed.value();
    arm_silence_timer();
    if ((f.params & nn::kParamModelsChanged) != 0) request_models(false);
    if ((f.params & (nn::kParamBitstreamChanged | nn::kParamEditMode)) != 0) revalidate();
    if (!table_) {
      ++owner_.natnet_counters_.frames_before_models;
      return;
    }
    if (last_frame_) {
      const std::int64_t diff = static_cast<std::int64_t>(f.frame_number) - *last_frame_;
      if (diff <= 0 && diff > -kRestartJump) {
        ++owner_.natnet_counters_.duplicate_frames;
        return;
      }
    }
    nn::MappedFrame mapped = nn::to_mocap_frame(f, *table_, info_->clock_hz);
    if (mapped.unknown_ids > 0) {
      owner_.natnet_counters_.unknown_ids += mapped.unknown_ids;
      request_models(false);  // §3.4: a body added since the last reload
    }
    owner_.natnet_counters_.invalid_poses += mapped.invalid_poses;
    // Every body unknown (the models were requested before Motive had them): nothing to deliver
    // yet; a frame that really has no rigid body is delivered.
    if (mapped.frame.bodies.empty() && !f.rigid_bodies.empty()) return;
    if (last_frame_ && last_timestamp_ && f.frame_number > *last_frame_) {
      const double dt = f.timestamp_s - *last_timestamp_;
      const auto frames = static_cast<double>(f.frame_number - *last_frame_);
      if (dt > 0.0 && frames < 100.0) rate_hz_ = frames / dt;
    }
    last_frame_ = f.frame_number;
    last_timestamp_ = f.timestamp_s;
    if (rate_hz_ > 0.0 && rate_hz_ < 100000.0) mapped.frame.frame_rate_hz = rate_hz_;
    ++owner_.counters_.frames;
    if (on_frame_) on_frame_(std::move(mapped.frame), io::host_now());
  }

  // §4.7: the bitstream may have changed (or Motive switched to Edit mode): ask for the server
  // info again and, from a NatNet 4 server, the "Bitstream" in force for this client, at most
  // every kRevalidateEvery; a new version reloads the model definitions.
  void revalidate() {
    const auto t = SteadyClock::now();
    if (t - last_revalidate_ < kRevalidateEvery) return;
    last_revalidate_ = t;
    ++owner_.natnet_counters_.revalidations;
    nn::ConnectRequest req;
    req.sender.name = "mocaplink";
    req.sender.natnet_version = {4, 1, 0, 0};
    send(nn::encode_connect(req));
    if (info_ && info_->version().at_least(4, 0)) {
      send(nn::encode_string_packet(nn::MessageId::request, "Bitstream"));
    }
  }

  void keep_alive_tick() {
    const auto gen = generation_;
    send(nn::encode_empty(nn::MessageId::keep_alive));
    ++owner_.natnet_counters_.keep_alives;
    keep_alive_timer_.expires_after(opts_.keep_alive);
    keep_alive_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (!ec && gen == generation_) keep_alive_tick();
    });
  }

  void arm_silence_timer() {
    const auto gen = generation_;
    silence_timer_.expires_after(opts_.silence_timeout);
    silence_timer_.async_wait([this, gen](const asio::error_code& ec) {
      if (ec || gen != generation_) return;
      ++owner_.natnet_counters_.timeouts;
      fail("no frame from the server for " + std::to_string(opts_.silence_timeout.count()) + " ms",
           false);
    });
  }

  void close_sockets() {
    asio::error_code ignored;
    resolver_.cancel();
    cmd_.socket.close(ignored);
    data_.socket.close(ignored);
  }

  // Drops the session and schedules the next attempt. Nothing of it survives: server info, model
  // table and frame numbers all come fresh from the next connection.
  void fail(const std::string& reason, bool is_malformed) {
    if (is_malformed) ++owner_.counters_.malformed;
    owner_.last_error_.set(reason);
    if (server_ && cmd_.socket.is_open() && !multicast_) {
      send(nn::encode_empty(nn::MessageId::disconnect));
    }
    ++generation_;
    close_sockets();
    info_.reset();
    table_.reset();
    last_frame_.reset();
    last_timestamp_.reset();
    connect_timer_.cancel();
    silence_timer_.cancel();
    keep_alive_timer_.cancel();
    state_(SourceState::disconnected, reason);
    retry_timer_.expires_after(backoff_.next());
    retry_timer_.async_wait([this](const asio::error_code& ec) {
      if (!ec) connect();
    });
  }

  NatnetSource& owner_;
  const NatnetSourceOptions& opts_;
  FrameSink on_frame_;
  StateReporter state_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  udp::resolver resolver_{io_};
  Receiver cmd_{io_};
  Receiver data_{io_};
  asio::steady_timer connect_timer_{io_};
  asio::steady_timer silence_timer_{io_};
  asio::steady_timer keep_alive_timer_{io_};
  asio::steady_timer retry_timer_{io_};
  std::optional<udp::endpoint> server_;
  std::uint16_t server_data_port_ = nn::kDefaultDataPort;  ///< its frames' source port (unicast)
  std::optional<nn::ServerInfo> info_;
  std::optional<nn::BodyTable> table_;
  bool multicast_ = true;
  std::string detail_;
  std::optional<std::int64_t> last_frame_;
  std::optional<double> last_timestamp_;
  double rate_hz_ = 0.0;
  SteadyClock::time_point last_model_request_{};
  SteadyClock::time_point last_revalidate_{};
  std::uint64_t generation_ = 0;
  std::uint64_t attempts_ = 0;
  core::RetrySchedule backoff_;
};

NatnetSource::NatnetSource(NatnetSourceOptions options, std::string url)
    : options_(std::move(options)), url_(std::move(url)) {}

NatnetSource::~NatnetSource() {
  stop();
}

void NatnetSource::start(FrameSink on_frame, StateSink on_state) {
  thread_.start_once(*this, std::move(on_frame), std::move(on_state));
}

void NatnetSource::stop() {
  thread_.stop();
}

}  // namespace mocaplink::sources

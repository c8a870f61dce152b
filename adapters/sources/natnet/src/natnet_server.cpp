#include "mocaplink/sources/natnet_server.hpp"

#include <array>
#include <map>
#include <set>
#include <utility>

#include <asio.hpp>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/natnet_mocap_frame.hpp"

namespace mocaplink::sources {

namespace nn = wire::natnet;
using asio::ip::udp;
using SteadyClock = std::chrono::steady_clock;

namespace {

constexpr std::uint64_t kClockHz = 10'000'000;
constexpr int kRepeatModelsChanged = 3;     // frames carrying the "models changed" bit
constexpr int kRepeatBitstreamChanged = 3;  // frames carrying the "bitstream changed" bit
constexpr std::array<nn::Version, 5> kServedVersions = {
    nn::Version{3, 0}, nn::Version{3, 1}, nn::Version{4, 0}, nn::Version{4, 1}, nn::Version{4, 2}};

std::optional<nn::Version> served_version(std::string_view text) {
  for (const nn::Version v : kServedVersions) {
    if (text == v.to_string()) return v;
  }
  return std::nullopt;
}

std::array<std::uint8_t, 4> octets(const std::string& ipv4) {
  asio::error_code ec;
  const auto b = asio::ip::make_address_v4(ipv4, ec).to_bytes();
  return {b[0], b[1], b[2], b[3]};
}

}  // namespace

std::variant<NatnetServerOptions, std::string> natnet_server_options(
    const EmulatorOptions& options) {
  NatnetServerOptions o;
  o.listen_host = options.listen_host;
  o.port = options.port;
  o.rate_hz = options.rate_hz;
  for (const auto& [key, value] : options.settings) {
    asio::error_code ec;
    if (key == "transport") {
      if (value != "multicast" && value != "unicast") {
        return "transport must be multicast or unicast, got " + config::quote(value);
      }
      o.multicast = value == "multicast";
    } else if (key == "group") {
      const auto g = asio::ip::make_address_v4(value, ec);
      if (ec || !g.is_multicast()) {
        return "group must be an IPv4 multicast address, got " + config::quote(value);
      }
      o.group = value;
    } else if (key == "interface") {
      (void)asio::ip::make_address_v4(value, ec);
      if (ec) return "interface must be an IPv4 address, got " + config::quote(value);
      o.interface = value;
    } else if (key == "data_port") {
      std::uint64_t port = 0;
      if (auto err = config::read_count_option(key, value, 1, 65535, port); !err.empty()) {
        return err;
      }
      o.data_port = static_cast<std::uint16_t>(port);
    } else if (key == "version") {
      const auto v = served_version(value);
      if (!v) return "version must be 3.0, 3.1, 4.0, 4.1 or 4.2, got " + config::quote(value);
      o.version = *v;
    } else if (key == "keepalive_timeout_s") {
      double s = 0.0;
      if (auto err = config::read_number_option(key, value, 0.1, 3600.0, true, s); !err.empty()) {
        return err;
      }
      o.keepalive_timeout = std::chrono::milliseconds(static_cast<std::int64_t>(s * 1000.0));
    } else if (key == "up") {
      if (value != "y" && value != "z") return "up must be y or z, got " + config::quote(value);
      o.y_up = value == "y";
    }
  }
  return o;
}

class NatnetServer::Impl {
 public:
  Impl(const NatnetServerOptions& options, NatnetServerCounters& counters)
      : options_(options), counters_(counters) {}

  std::optional<std::string> open() {
    asio::error_code ec;
    const auto address = asio::ip::make_address_v4(options_.listen_host, ec);
    if (ec) return "bad listen address '" + options_.listen_host + "': " + ec.message();
    if (command_.open(udp::v4(), ec); ec) return "socket: " + ec.message();
    if (command_.bind(udp::endpoint(address, options_.port), ec); ec) {
      return "cannot listen on " + options_.listen_host + ":" + std::to_string(options_.port) +
             ": " + ec.message();
    }
    if (!options_.multicast) {
      // Motive sends unicast frames from its data port, and OptiTrack's NatNet library drops
      // frames that come from the command port (docs/sources.md "Where unicast frames come from").
      if (data_.open(udp::v4(), ec); ec) return "data socket: " + ec.message();
      // A client on this host may bind the same port (mocaplink's does, SO_REUSEADDR): it never
      // receives on it from us, so sharing it harms nothing.
      data_.set_option(udp::socket::reuse_address(true), ec);
      if (data_.bind(udp::endpoint(address, options_.data_port), ec); ec) {
        return "cannot send from data port " + options_.listen_host + ":" +
               std::to_string(options_.data_port) + ": " + ec.message() +
               " (--set data_port=N for another)";
      }
      return std::nullopt;
    }
    if (multicast_.open(udp::v4(), ec); ec) return "multicast socket: " + ec.message();
    group_ = udp::endpoint(asio::ip::make_address_v4(options_.group, ec), options_.data_port);
    multicast_.set_option(asio::ip::multicast::hops(1), ec);
    multicast_.set_option(asio::ip::multicast::enable_loopback(true), ec);
    if (!options_.interface.empty()) {
      multicast_.set_option(
          asio::ip::multicast::outbound_interface(asio::ip::make_address_v4(options_.interface)),
          ec);
      if (ec) return "multicast interface " + options_.interface + ": " + ec.message();
    }
    return std::nullopt;
  }

  std::uint16_t bound_port() const { return command_.local_endpoint().port(); }
  /// The data port frames leave from: options_.data_port, or the one chosen for 0 (unicast).
  std::uint16_t data_port() const {
    asio::error_code ec;
    const auto local = data_.local_endpoint(ec);
    return ec ? options_.data_port : local.port();
  }

  void run(FrameProvider provider) {
    provider_ = std::move(provider);
    receive();
    if (provider_) tick();
    io_.run();
    asio::error_code ignored;
    command_.close(ignored);
    data_.close(ignored);
    multicast_.close(ignored);
  }

  void stop() { io_.stop(); }

  void publish(core::MocapFrame frame) {
    asio::post(io_, [this, f = std::move(frame)] { produce(f); });
  }

 private:
  // A unicast client: the endpoint its NAT_CONNECT came from, which is where Motive streams.
  struct Client {
    SteadyClock::time_point last_heard;  ///< its NAT_CONNECT or last NAT_KEEPALIVE
    nn::Version version;                 ///< its bitstream ("Bitstream,X.Y" changes only its own)
    int bitstream_changed_left = 0;      ///< frames still to carry the "bitstream changed" bit
  };

  void tick() {
    tick_timer_.expires_after(std::chrono::duration_cast<SteadyClock::duration>(
        std::chrono::duration<double>(1.0 / options_.rate_hz)));
    tick_timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      if (auto frame = provider_(ticks_++)) produce(*frame);
      tick();
    });
  }

  void produce(const core::MocapFrame& frame) {
    nn::FrameOfData f = models_.frame_of(frame, options_.y_up, kClockHz);
    if ((f.params & nn::kParamModelsChanged) != 0) models_changed_left_ = kRepeatModelsChanged;
    if (models_changed_left_ > 0) {
      f.params |= nn::kParamModelsChanged;
      --models_changed_left_;
    }
    ++counters_.frames;
    asio::error_code ignored;
    if (options_.multicast) {
      multicast_.send_to(asio::buffer(nn::encode_frame(f, options_.version)), group_, 0, ignored);
      ++counters_.datagrams_sent;
      return;
    }
    expire_clients();
    // One encoding per (version, flag) in use: clients may have asked for different bitstreams.
    std::map<std::pair<nn::Version, bool>, std::vector<std::byte>> packets;
    for (auto& [endpoint, client] : clients_) {
      const bool changed = client.bitstream_changed_left > 0;
      if (changed) --client.bitstream_changed_left;
      auto [it, fresh] = packets.try_emplace({client.version, changed});
      if (fresh) {
        nn::FrameOfData g = f;
        if (changed) g.params |= nn::kParamBitstreamChanged;
        it->second = nn::encode_frame(g, client.version);
      }
      data_.send_to(asio::buffer(it->second), endpoint, 0, ignored);
      ++counters_.datagrams_sent;
    }
  }

  // A unicast client not heard from (keep-alive) for keepalive_timeout is told so with
  // NAT_DISCONNECTBYTIMEOUT and no longer served, as Motive does after about 10 s.
  void expire_clients() {
    const auto now = SteadyClock::now();
    std::vector<udp::endpoint> expired;
    for (auto it = clients_.begin(); it != clients_.end();) {
      if (now - it->second.last_heard > options_.keepalive_timeout) {
        expired.push_back(it->first);
        it = clients_.erase(it);
      } else {
        ++it;
      }
    }
    // Counted before the clients are told, so that what they see agrees with the counters.
    counters_.clients_timed_out += expired.size();
    counters_.clients_now = clients_.size();
    asio::error_code ignored;
    for (const auto& endpoint : expired) {
      command_.send_to(asio::buffer(nn::encode_empty(nn::MessageId::disconnect_by_timeout)),
                       endpoint, 0, ignored);
    }
  }

  void receive() {
    command_.async_receive_from(asio::buffer(buffer_), from_,
                                [this](const asio::error_code& ec, std::size_t n) {
                                  if (ec == asio::error::operation_aborted) return;
                                  if (!ec) on_request(std::span(buffer_.data(), n));
                                  receive();
                                });
  }

  void reply(const std::vector<std::byte>& packet) {
    asio::error_code ignored;
    command_.send_to(asio::buffer(packet), from_, 0, ignored);
  }

  // The server info a client gets: its own bitstream version (unicast) or the stream's.
  nn::ServerInfo server_info(nn::Version version) const {
    nn::ServerInfo info;
    info.sender.name = "mocaplink NatNet emulator";
    info.sender.app_version = {3, 1, 0, 0};
    info.sender.natnet_version = {version.major, version.minor, 0, 0};
    info.has_connection_info = true;
    info.clock_hz = kClockHz;
    info.data_port = options_.multicast ? options_.data_port : data_port();
    info.multicast = options_.multicast;
    info.multicast_group = octets(options_.group);
    return info;
  }

  void on_request(std::span<const std::byte> bytes) {
    auto packet = nn::split_packet(bytes);
    if (!packet) {
      ++counters_.malformed_requests;
      return;
    }
    const auto payload = packet.value().payload;
    switch (static_cast<nn::MessageId>(packet.value().id)) {
      case nn::MessageId::connect:
      case nn::MessageId::discovery: {
        if (!nn::parse_connect(payload)) {
          ++counters_.malformed_requests;
          return;
        }
        nn::Version version = options_.version;
        if (!options_.multicast && packet.value().id == 0) {
          auto it = clients_.find(from_);
          if (it == clients_.end()) {
            if (clients_.size() >= options_.max_clients) {
              ++counters_.clients_rejected;
              return;
            }
            // A new client; a repeated NAT_CONNECT keeps its bitstream and, as with Motive, does
            // not count as a keep-alive.
            it = clients_.emplace(from_, Client{SteadyClock::now(), options_.version, 0}).first;
          }
          version = it->second.version;
          counters_.clients_now = clients_.size();
        }
        ++counters_.clients_connected;
        return reply(nn::encode_server_info(server_info(version)));
      }
      case nn::MessageId::keep_alive:
        if (auto it = clients_.find(from_); it != clients_.end()) {
          it->second.last_heard = SteadyClock::now();
        }
        return;
      case nn::MessageId::disconnect:
        clients_.erase(from_);
        counters_.clients_now = clients_.size();
        return;
      case nn::MessageId::request_model_def:
        ++counters_.model_requests;
        return reply(nn::encode_model_definitions(models_.definitions(), version_of(from_)));
      case nn::MessageId::echo_request: {
        auto value = nn::parse_echo_request(payload);
        if (!value) {
          ++counters_.malformed_requests;
          return;
        }
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                            SteadyClock::now().time_since_epoch())
                            .count();
        return reply(nn::encode_echo_response(
            {value.value(), static_cast<std::uint64_t>(ns) / (1'000'000'000 / kClockHz)}));
      }
      case nn::MessageId::request:
        return on_command(payload);
      default:
        ++counters_.malformed_requests;
        return;
    }
  }

  // The bitstream `endpoint` is served in: its own (unicast client) or the stream's.
  nn::Version version_of(const udp::endpoint& endpoint) const {
    const auto it = clients_.find(endpoint);
    return it != clients_.end() ? it->second.version : options_.version;
  }

  static std::vector<std::byte> result_code(std::int32_t result) {
    std::vector<std::byte> code;
    for (int i = 0; i < 4; ++i) {
      code.push_back(static_cast<std::byte>((result >> (8 * i)) & 0xFF));
    }
    return nn::encode_packet(nn::MessageId::response, code);
  }

  // §2.3 / §1.2: "Bitstream" (query) and "Bitstream,X.Y[.Z]" (select); nothing else is known.
  // Unicast: only a connected client is answered (every official client connects first), and
  // "Bitstream,X.Y" changes that client's bitstream alone, flagging its next frames (§4.7).
  // Multicast: the one stream is shared, so a change is refused (the samples say the command
  // needs unicast).
  void on_command(std::span<const std::byte> payload) {
    auto text = nn::parse_string_payload(payload);
    if (!text) {
      ++counters_.malformed_requests;
      return;
    }
    const auto client = clients_.find(from_);
    if (!options_.multicast && client == clients_.end()) {
      ++counters_.requests_refused;
      return;
    }
    const std::string& cmd = text.value();
    if (cmd == "Bitstream") {
      // No NUL: OptiTrack's Python client cannot read one (nn::encode_response_text).
      return reply(nn::encode_response_text("Bitstream," + version_of(from_).to_string() + ".0"));
    }
    if (cmd.rfind("Bitstream,", 0) == 0) {
      std::string wanted = cmd.substr(10);
      if (std::count(wanted.begin(), wanted.end(), '.') == 2) {
        wanted = wanted.substr(0, wanted.rfind('.'));
      }
      const auto v = served_version(wanted);
      if (!v || options_.multicast) {
        ++counters_.requests_refused;
        return reply(result_code(1));
      }
      if (client->second.version != *v) {
        client->second.version = *v;
        client->second.bitstream_changed_left = kRepeatBitstreamChanged;
      }
      return reply(result_code(0));
    }
    reply(nn::encode_empty(nn::MessageId::unrecognized_request));
  }

  const NatnetServerOptions& options_;
  NatnetServerCounters& counters_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  udp::socket command_{io_};
  udp::socket data_{io_};  // unicast: frames leave from the data port
  udp::socket multicast_{io_};
  udp::endpoint group_;
  udp::endpoint from_;
  std::vector<std::byte> buffer_ = std::vector<std::byte>(nn::kMaxDatagramBytes);
  asio::steady_timer tick_timer_{io_};
  FrameProvider provider_;
  std::uint64_t ticks_ = 0;
  nn::ServedModels models_;
  int models_changed_left_ = 0;
  std::map<udp::endpoint, Client> clients_;
};

NatnetServer::NatnetServer(NatnetServerOptions options) : options_(std::move(options)) {}

NatnetServer::~NatnetServer() {
  stop();
}

std::optional<std::string> NatnetServer::start(FrameProvider provider) {
  if (impl_) return "already started";
  if (!(options_.rate_hz > 0.0 && options_.rate_hz <= 10000.0)) {
    return "rate must be in (0, 10000] Hz";
  }
  impl_ = std::make_unique<Impl>(options_, counters_);
  if (auto err = impl_->open()) {
    impl_.reset();
    return err;
  }
  port_ = impl_->bound_port();
  data_port_ = impl_->data_port();
  thread_ = std::thread([this, p = std::move(provider)]() mutable { impl_->run(std::move(p)); });
  return std::nullopt;
}

void NatnetServer::publish(core::MocapFrame frame) {
  if (impl_) impl_->publish(std::move(frame));
}

void NatnetServer::stop() {
  if (!impl_) return;
  impl_->stop();
  if (thread_.joinable()) thread_.join();
  impl_.reset();
}

std::string NatnetServer::summary() const {
  const auto& c = counters_;
  return std::to_string(c.frames.load()) + " frames, " +
         std::to_string(c.clients_connected.load()) + " clients connected, " +
         std::to_string(c.clients_timed_out.load()) + " timed out, " +
         std::to_string(c.requests_refused.load()) + " requests refused, " +
         std::to_string(c.malformed_requests.load()) + " malformed requests";
}

}  // namespace mocaplink::sources

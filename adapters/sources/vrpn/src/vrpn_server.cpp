#include "mocaplink/sources/vrpn_server.hpp"

#include <array>
#include <chrono>
#include <deque>
#include <map>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/sources/emulator_support.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::sources {

namespace vr = wire::vrpn;
using asio::ip::tcp;
using SteadyClock = std::chrono::steady_clock;

namespace {

// The types a VRPN tracker server registers (§4.1, §5.4), in the order our ids give them.
constexpr std::array<std::string_view, 18> kTypes = {
    "VRPN_Connection_Got_First_Connection",
    "VRPN_Connection_Got_Connection",
    "VRPN_Connection_Dropped_Connection",
    "VRPN_Connection_Dropped_Last_Connection",
    vr::kPosQuatType,
    vr::kVelocityType,
    "vrpn_Tracker Acceleration",
    "vrpn_Tracker To_Room",
    "vrpn_Tracker Unit_To_Sensor",
    "vrpn_Tracker Request_Tracker_To_Room",
    "vrpn_Tracker Request_Unit_To_Sensor",
    "vrpn_Tracker Workspace",
    "vrpn_Tracker Request_Tracker_Workspace",
    "vrpn_Tracker set_update_rate",
    "vrpn_Tracker Reset_Origin",
    "vrpn_Base text_message",
    "vrpn_Base ping_message",
    "vrpn_Base pong_message",
};
constexpr std::int32_t kPosQuatId = 4;
constexpr std::int32_t kVelocityId = 5;
constexpr std::string_view kControlSender = "VRPN Control";

std::int64_t wall_clock_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

vr::Timeval timeval_of(std::int64_t us) {
  return vr::Timeval{static_cast<std::uint32_t>(us / 1'000'000),
                     static_cast<std::uint32_t>(us % 1'000'000)};
}

vr::Timeval wall_clock() {
  return timeval_of(wall_clock_us());
}

}  // namespace

class VrpnServer::Impl {
 public:
  Impl(const VrpnServerOptions& options, VrpnServerCounters& counters, FrameProvider provider)
      : options_(options), counters_(counters), provider_(std::move(provider)) {}

  std::optional<std::string> open() {
    return listen_tcp(acceptor_, options_.listen_host, options_.port);
  }
  std::uint16_t local_port() const { return acceptor_.local_endpoint().port(); }

  void run() {
    accept();
    if (provider_) {
      schedule_.emplace(options_.rate_hz, SteadyClock::now());
      next_tick();
    }
    io_.run();
    for (const auto& c : clients_) close_socket(*c);
    clients_.clear();
    asio::error_code ignored;
    acceptor_.close(ignored);
  }

  void stop() { io_.stop(); }

  void publish(core::MocapFrame frame) {
    asio::post(io_, [this, f = std::move(frame)] { produce(f); });
  }

 private:
  struct Client {
    explicit Client(tcp::socket s) : socket(std::move(s)) {}
    tcp::socket socket;
    std::array<std::byte, vr::kCookieBytes> cookie{};
    std::array<std::byte, vr::kHeaderBytes> header{};
    std::vector<std::byte> payload;
    std::deque<std::vector<std::byte>> out;
    bool ready = false;  // cookie accepted, descriptions sent
    bool sending = false;
    bool gone = false;
    std::uint32_t sequence = 0;
  };
  using ClientPtr = std::shared_ptr<Client>;

  static void close_socket(Client& c) {
    asio::error_code ignored;
    c.socket.shutdown(tcp::socket::shutdown_both, ignored);
    c.socket.close(ignored);
  }

  void next_tick() {
    timer_.expires_at(schedule_->due());
    timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      if (auto frame = provider_(schedule_->tick())) produce(*frame);
      schedule_->advance(SteadyClock::now());
      next_tick();
    });
  }

  std::int32_t sender_id(const std::string& name) {
    auto it = senders_.find(name);
    if (it != senders_.end()) return it->second;
    const auto id = static_cast<std::int32_t>(sender_order_.size());
    senders_.emplace(name, id);
    sender_order_.push_back(name);
    const auto now = wall_clock();
    for (const auto& c : clients_) {
      if (c->ready) send(c, vr::encode_description(now, vr::kSenderDescription, id, name));
    }
    return id;
  }

  // A report is stamped with the wall-clock time of its frame's capture, as a server stamps its
  // camera frames: the first frame's capture is "now", later ones follow their capture times
  // (re-anchored when capture time goes back, a replay starting again).
  vr::Timeval stamp(const core::MocapFrame& frame) {
    const std::int64_t capture_us =
        std::chrono::duration_cast<std::chrono::microseconds>(frame.capture_time.time_since_epoch())
            .count();
    if (!anchor_ || capture_us < anchor_->first) anchor_ = std::pair{capture_us, wall_clock_us()};
    return timeval_of(anchor_->second + (capture_us - anchor_->first));
  }

  void produce(const core::MocapFrame& frame) {
    ++counters_.frames;
    const auto now = stamp(frame);
    const double dt = 1.0 / options_.rate_hz;
    for (const auto& body : frame.bodies) {
      if (!body.tracked || body.name.empty() || body.name.size() >= vr::kMaxNameBytes) continue;
      const std::int32_t id = sender_id(body.name);
      const auto pose = vr::encode_pos_quat(vr::PosQuat{0, body.p_world_m, body.q_world_body});
      const auto velocity = vr::encode_velocity(0, Eigen::Vector3d::Zero(), dt);
      const std::vector<ClientPtr> all(clients_.begin(), clients_.end());
      for (const auto& c : all) {
        if (!c->ready) continue;
        send(c, vr::encode_message(now, id, kPosQuatId, pose, c->sequence++));
        send(c, vr::encode_message(now, id, kVelocityId, velocity, c->sequence++));
        ++counters_.reports;
      }
    }
  }

  void accept() {
    acceptor_.async_accept([this](const asio::error_code& ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec) admit(std::move(socket));
      accept();
    });
  }

  void admit(tcp::socket socket) {
    asio::error_code ignored;
    if (clients_.size() >= options_.max_clients) {
      ++counters_.clients_rejected;
      socket.close(ignored);
      return;
    }
    socket.set_option(tcp::no_delay(true), ignored);
    auto c = std::make_shared<Client>(std::move(socket));
    clients_.insert(c);
    ++counters_.clients_accepted;
    counters_.clients_now = clients_.size();
    const auto cookie = vr::make_cookie('0');
    send(c, std::vector<std::byte>(cookie.begin(), cookie.end()));
    asio::async_read(c->socket, asio::buffer(c->cookie),
                     [this, c](const asio::error_code& rec, std::size_t) {
                       if (rec || c->gone) return drop(c);
                       if (!vr::parse_cookie(c->cookie)) {
                         ++counters_.bad_cookies;
                         return drop(c);
                       }
                       describe_all(c);
                       read_header(c);
                     });
  }

  // §4.1: every sender, then every type (no UDP description: we serve TCP only).
  void describe_all(const ClientPtr& c) {
    const auto now = wall_clock();
    for (std::size_t i = 0; i < sender_order_.size(); ++i) {
      send(c, vr::encode_description(now, vr::kSenderDescription, static_cast<std::int32_t>(i),
                                     sender_order_[i], c->sequence++));
    }
    for (std::size_t i = 0; i < kTypes.size(); ++i) {
      send(c, vr::encode_description(now, vr::kTypeDescription, static_cast<std::int32_t>(i),
                                     kTypes[i], c->sequence++));
    }
    c->ready = true;
  }

  void read_header(const ClientPtr& c) {
    asio::async_read(c->socket, asio::buffer(c->header),
                     [this, c](const asio::error_code& ec, std::size_t) {
                       if (ec || c->gone) return drop(c);
                       auto header = vr::parse_header(c->header);
                       if (!header) return drop(c);
                       c->payload.resize(header.value().padded_payload_bytes());
                       asio::async_read(c->socket, asio::buffer(c->payload),
                                        [this, c](const asio::error_code& pec, std::size_t) {
                                          if (pec || c->gone) return drop(c);
                                          read_header(c);  // client messages are ignored
                                        });
                     });
  }

  void send(const ClientPtr& c, std::vector<std::byte> message) {
    if (c->gone) return;
    if (c->out.size() >= options_.queue_messages) {
      ++counters_.slow_clients;
      return drop(c);
    }
    c->out.push_back(std::move(message));
    if (!c->sending) write(c);
  }

  void write(const ClientPtr& c) {
    if (c->out.empty() || c->gone) {
      c->sending = false;
      return;
    }
    c->sending = true;
    asio::async_write(c->socket, asio::buffer(c->out.front()),
                      [this, c](const asio::error_code& ec, std::size_t) {
                        if (ec || c->gone) return drop(c);
                        c->out.pop_front();
                        write(c);
                      });
  }

  void drop(const ClientPtr& c) {
    if (c->gone) return;
    c->gone = true;
    close_socket(*c);
    clients_.erase(c);
    counters_.clients_now = clients_.size();
  }

  const VrpnServerOptions& options_;
  VrpnServerCounters& counters_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  tcp::acceptor acceptor_{io_};
  asio::steady_timer timer_{io_};
  std::set<ClientPtr> clients_;
  FrameProvider provider_;
  std::optional<TickSchedule> schedule_;
  std::optional<std::pair<std::int64_t, std::int64_t>> anchor_;  // (capture µs, wall-clock µs)
  std::map<std::string, std::int32_t> senders_;
  std::vector<std::string> sender_order_{std::string(kControlSender)};
};

VrpnServer::VrpnServer(VrpnServerOptions options) : options_(std::move(options)) {}

VrpnServer::~VrpnServer() {
  stop();
}

std::optional<std::string> VrpnServer::start(FrameProvider provider) {
  return start_emulator(worker_, options_.rate_hz,
                        std::make_unique<Impl>(options_, counters_, std::move(provider)), port_);
}

void VrpnServer::publish(core::MocapFrame frame) {
  if (auto* impl = worker_.get()) impl->publish(std::move(frame));
}

void VrpnServer::stop() {
  worker_.stop();
}

std::string VrpnServer::summary() const {
  const auto& c = counters_;
  return std::to_string(c.frames.load()) + " frames, " + std::to_string(c.clients_accepted.load()) +
         " clients, " + std::to_string(c.reports.load()) + " reports, " +
         std::to_string(c.bad_cookies.load()) + " bad cookies, " +
         std::to_string(c.slow_clients.load()) + " slow clients";
}

}  // namespace mocaplink::sources

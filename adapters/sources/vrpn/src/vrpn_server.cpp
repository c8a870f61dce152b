#include "mocaplink/sources/vrpn_server.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <deque>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/sources/emulator_support.hpp"
#include "mocaplink/wire/vrpn_client.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::sources {

namespace vr = wire::vrpn;
using asio::ip::tcp;
using asio::ip::udp;
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
    vr::kPingType,
    vr::kPongType,
};
constexpr std::int32_t kPosQuatId = 4;
constexpr std::int32_t kVelocityId = 5;
constexpr std::int32_t kPongId = 17;
static_assert(kTypes[kPosQuatId] == vr::kPosQuatType && kTypes[kVelocityId] == vr::kVelocityType &&
              kTypes[kPongId] == vr::kPongType);
constexpr std::string_view kControlSender = "VRPN Control";
/// A body's velocity is the difference from its previous report at most this old (a longer gap:
/// zero velocity, as a server that has just (re)acquired it).
constexpr double kMaxVelocityGapS = 0.5;

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

/// The TCP port a VRPN client's connection request ("lob") asks to be called back at: the
/// datagram is "HOST PORT" and a NUL (vrpn_udp_request_lob_packet). As
/// server_check_for_incoming_connections, HOST must be letters, digits and dots and PORT at least
/// 1024; nullopt otherwise.
std::optional<std::uint16_t> parse_lob(std::string_view datagram) {
  datagram = datagram.substr(0, datagram.find('\0'));
  const auto space = datagram.find(' ');
  if (space == std::string_view::npos || space == 0) return std::nullopt;
  for (const char c : datagram.substr(0, space)) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.') return std::nullopt;
  }
  const auto digits = datagram.substr(space + 1);
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
  if (ec != std::errc{} || end != digits.data() + digits.size()) return std::nullopt;
  if (port < 1024 || port > 65535) return std::nullopt;
  return static_cast<std::uint16_t>(port);
}

}  // namespace

class VrpnServer::Impl {
 public:
  Impl(const VrpnServerOptions& options, VrpnServerCounters& counters, FrameProvider provider)
      : options_(options), counters_(counters), provider_(std::move(provider)) {}

  std::optional<std::string> open() {
    if (auto err = listen_tcp(acceptor_, options_.listen_host, options_.port)) return err;
    // The UDP port of the same number, where VRPN clients without tcp:// in their address ask to
    // be called back (vrpn.md §1.2). A port taken by someone else only costs that way in.
    asio::error_code ec;
    const udp::endpoint at(acceptor_.local_endpoint().address(), local_port());
    lob_.open(at.protocol(), ec);
    if (!ec) lob_.bind(at, ec);
    if (ec) lob_.close(ec);
    return std::nullopt;
  }
  std::uint16_t local_port() const { return acceptor_.local_endpoint().port(); }

  void run() {
    accept();
    if (lob_.is_open()) receive_lob();
    if (provider_) {
      schedule_.emplace(options_.rate_hz, SteadyClock::now());
      next_tick();
    }
    io_.run();
    for (const auto& c : clients_) close_socket(*c);
    clients_.clear();
    asio::error_code ignored;
    acceptor_.close(ignored);
    lob_.close(ignored);
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
    // The client's own sender and type ids (it describes them after its cookie, as every VRPN
    // endpoint does), kept to recognise its pings; at most wire::vrpn::kMaxIds each.
    std::unordered_map<std::int32_t, std::string> remote_senders;
    std::unordered_map<std::int32_t, std::string> remote_types;
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

  // A body's velocity as a tracker server derives it: the difference from its previous report
  // (position over the capture-time step; vel_quat = q · q_prev⁻¹ over the same step, the rotation
  // vrpn_Tracker_Filter applies to predict). Zero, identity and one frame period without one.
  struct Motion {
    Eigen::Vector3d v_m_s = Eigen::Vector3d::Zero();
    Eigen::Quaterniond vel_quat = Eigen::Quaterniond::Identity();
    double dt_s = 0.0;
  };
  Motion motion(const core::BodySample& body, core::SourceTime capture) {
    Motion m;
    m.dt_s = 1.0 / options_.rate_hz;
    auto [it, first] =
        previous_.try_emplace(body.name, Previous{body.p_world_m, body.q_world_body, capture});
    if (!first) {
      const double dt = std::chrono::duration<double>(capture - it->second.capture).count();
      if (dt > 0.0 && dt <= kMaxVelocityGapS) {
        m.v_m_s = (body.p_world_m - it->second.p_m) / dt;
        m.vel_quat = (body.q_world_body * it->second.q.conjugate()).normalized();
        if (m.vel_quat.w() < 0) m.vel_quat.coeffs() = -m.vel_quat.coeffs();
        m.dt_s = dt;
      }
      it->second = Previous{body.p_world_m, body.q_world_body, capture};
    }
    return m;
  }

  // A frame's reports go to each client in one write, as a VRPN server sends what a mainloop
  // packed (vrpn_Endpoint::send_pending_reports), so a client reads them together.
  void produce(const core::MocapFrame& frame) {
    ++counters_.frames;
    const auto now = stamp(frame);
    struct Out {
      std::int32_t id;
      std::vector<std::byte> pose, velocity;
    };
    std::vector<Out> reports;
    for (const auto& body : frame.bodies) {
      if (!body.tracked || body.name.empty() || body.name.size() >= vr::kMaxNameBytes) continue;
      const std::int32_t id = sender_id(body.name);
      const Motion m = motion(body, frame.capture_time);
      reports.push_back(Out{id,
                            vr::encode_pos_quat(vr::PosQuat{0, body.p_world_m, body.q_world_body}),
                            vr::encode_velocity(0, m.v_m_s, m.vel_quat, m.dt_s)});
    }
    if (reports.empty()) return;
    const std::vector<ClientPtr> all(clients_.begin(), clients_.end());
    for (const auto& c : all) {
      if (!c->ready) continue;
      std::vector<std::byte> bytes;
      for (const auto& r : reports) {
        for (const auto& [type, payload] :
             {std::pair{kPosQuatId, &r.pose}, std::pair{kVelocityId, &r.velocity}}) {
          const auto message = vr::encode_message(now, r.id, type, *payload, c->sequence++);
          bytes.insert(bytes.end(), message.begin(), message.end());
        }
      }
      send(c, std::move(bytes));
      counters_.reports += reports.size();
    }
  }

  void accept() {
    acceptor_.async_accept([this](const asio::error_code& ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec) admit(std::move(socket));
      accept();
    });
  }

  // A connection request: connect to the port it names, at the address it came from (VRPN
  // connects to the host the datagram names; the source address is the same for a client on one
  // interface, and no datagram makes us connect to a third host), then serve it as an accepted
  // client. A request for a callback already under way is ignored (the client repeats it every
  // 2 s until called back).
  void receive_lob() {
    lob_.async_receive_from(
        asio::buffer(lob_buffer_), lob_from_, [this](const asio::error_code& ec, std::size_t n) {
          if (ec == asio::error::operation_aborted) return;
          if (!ec) {
            const auto port = parse_lob(std::string_view(lob_buffer_.data(), n));
            if (!port) {
              ++counters_.bad_lobs;
            } else {
              call_back(tcp::endpoint(lob_from_.address(), *port));
            }
          }
          receive_lob();
        });
  }

  void call_back(const tcp::endpoint& to) {
    if (!calling_.insert(to).second) return;
    auto socket = std::make_shared<tcp::socket>(io_);
    socket->async_connect(to, [this, socket, to](const asio::error_code& ec) {
      calling_.erase(to);
      if (ec) return;
      ++counters_.lobs_answered;
      admit(std::move(*socket));
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
    asio::async_read(
        c->socket, asio::buffer(c->header), [this, c](const asio::error_code& ec, std::size_t) {
          if (ec || c->gone) return drop(c);
          auto header = vr::parse_header(c->header);
          if (!header) return drop(c);
          c->payload.resize(header.value().padded_payload_bytes());
          asio::async_read(c->socket, asio::buffer(c->payload),
                           [this, c, h = header.value()](const asio::error_code& pec, std::size_t) {
                             if (pec || c->gone) return drop(c);
                             on_client_message(c, h);
                             read_header(c);
                           });
        });
  }

  // What a VRPN server does with a client's messages, as far as a tracker client needs: its
  // sender and type descriptions are remembered, and a "vrpn_Base ping_message" from a sender
  // named like one of our trackers is answered at once with a "vrpn_Base pong_message" from that
  // tracker (vrpn_BaseClassUnique::handle_ping, registered for the device's sender id). Without
  // the pong a VRPN client warns "No response from server" after 3 s and gives the server up as
  // dead after 10 s. Everything else (UDP and log descriptions, other messages) is ignored.
  void on_client_message(const ClientPtr& c, const vr::Header& header) {
    const std::span<const std::byte> payload(c->payload.data(), header.payload_bytes());
    if (header.type == vr::kSenderDescription || header.type == vr::kTypeDescription) {
      auto name = vr::parse_description(payload);
      auto& table = header.type == vr::kSenderDescription ? c->remote_senders : c->remote_types;
      if (name && (table.size() < vr::kMaxIds || table.contains(header.sender))) {
        table[header.sender] = std::move(name).value();
      }
      return;
    }
    if (header.type < 0) return;
    const auto type = c->remote_types.find(header.type);
    const auto sender = c->remote_senders.find(header.sender);
    if (type == c->remote_types.end() || type->second != vr::kPingType ||
        sender == c->remote_senders.end() || sender->second == kControlSender) {
      return;
    }
    const auto ours = senders_.find(sender->second);
    if (ours == senders_.end()) return;  // no such tracker here: a VRPN server has no handler
    ++counters_.pongs;
    send(c, vr::encode_message(wall_clock(), ours->second, kPongId, {}, c->sequence++));
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
  udp::socket lob_{io_};
  std::array<char, 200> lob_buffer_{};
  udp::endpoint lob_from_;
  std::set<tcp::endpoint> calling_;  // callbacks being connected
  std::map<std::string, std::int32_t> senders_;
  struct Previous {
    Eigen::Vector3d p_m;
    Eigen::Quaterniond q;
    core::SourceTime capture;
  };
  std::map<std::string, Previous> previous_;  // each body's last report (velocity)
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
         std::to_string(c.slow_clients.load()) + " slow clients, " +
         std::to_string(c.pongs.load()) + " pings answered, " +
         std::to_string(c.lobs_answered.load()) + " UDP connection requests answered";
}

}  // namespace mocaplink::sources

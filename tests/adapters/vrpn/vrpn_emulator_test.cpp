// The VRPN tracker emulator as a VRPN library client sees it, from a raw client on 127.0.0.1
// written from vrpn.md and vrpn_BaseClass.C (not our vrpn:// source): it answers the client's
// "vrpn_Base ping_message" with a "vrpn_Base pong_message" from the same tracker (else a real
// client warns "No response from server" and gives it up), and its `vrpn_Tracker Velocity`
// reports carry the simulated body's motion. Waits are on conditions, never timing assertions.
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <gtest/gtest.h>
#include <asio.hpp>

#include "mocaplink/sources/sim_world.hpp"
#include "mocaplink/sources/vrpn_server.hpp"
#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::sources {
namespace {

namespace vr = wire::vrpn;
using asio::ip::tcp;

/// One message as read: header, the sender and type names the server described, payload.
struct Message {
  vr::Header header;
  std::string sender, type;
  std::vector<std::byte> payload;
};

/// A blocking raw VRPN client: cookie both ways, then messages with the server's id tables.
class RawClient {
 public:
  explicit RawClient(std::uint16_t port) {
    socket_.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
    const auto cookie = vr::make_cookie('0');
    asio::write(socket_, asio::buffer(cookie));
    std::array<std::byte, vr::kCookieBytes> theirs{};
    asio::read(socket_, asio::buffer(theirs));
    EXPECT_TRUE(vr::parse_cookie(theirs));
  }
  void send(const std::vector<std::byte>& bytes) { asio::write(socket_, asio::buffer(bytes)); }
  Message read() {
    std::array<std::byte, vr::kHeaderBytes> h{};
    asio::read(socket_, asio::buffer(h));
    auto header = vr::parse_header(h);
    EXPECT_TRUE(header);
    Message m{header.value(), "", "", {}};
    std::vector<std::byte> padded(m.header.padded_payload_bytes());
    asio::read(socket_, asio::buffer(padded));
    m.payload.assign(padded.begin(),
                     padded.begin() + static_cast<std::ptrdiff_t>(m.header.payload_bytes()));
    if (m.header.type == vr::kSenderDescription || m.header.type == vr::kTypeDescription) {
      auto name = vr::parse_description(m.payload);
      EXPECT_TRUE(name);
      (m.header.type == vr::kSenderDescription ? senders_ : types_)[m.header.sender] = name.value();
    } else if (m.header.type >= 0) {
      m.sender = senders_.count(m.header.sender) ? senders_[m.header.sender] : "";
      m.type = types_.count(m.header.type) ? types_[m.header.type] : "";
    }
    return m;
  }
  /// Reads until a message of `type` from `sender` ("" = any); nullopt after `limit` messages.
  std::optional<Message> read_until(std::string_view type, std::string_view sender = "",
                                    int limit = 5000) {
    for (int i = 0; i < limit; ++i) {
      Message m = read();
      if (m.type == type && (sender.empty() || m.sender == sender)) return m;
    }
    return std::nullopt;
  }

 private:
  asio::io_context io_;
  tcp::socket socket_{io_};
  std::unordered_map<std::int32_t, std::string> senders_, types_;
};

SimOptions still_sim() {
  SimOptions o;
  o.bodies = 3;
  o.rate_hz = 200.0;
  o.noise_mm = 0.0;
  o.noise_deg = 0.0;
  return o;
}

std::unique_ptr<VrpnServer> serve_sim(const SimWorld& world) {
  VrpnServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = 0;
  o.rate_hz = world.config().rate_hz;
  auto server = std::make_unique<VrpnServer>(o);
  const auto err = server->start([&world](std::uint64_t tick) {
    return std::optional<core::MocapFrame>(world.frame(tick + 1));
  });
  EXPECT_FALSE(err.has_value()) << *err;
  return server;
}

/// What vrpn_BaseClassUnique::initiate_ping_cycle sends, after the client's own descriptions
/// (its connection describes every sender and type it registered, as the server does).
std::vector<std::byte> ping_from(const std::string& tracker) {
  std::vector<std::byte> out;
  for (const auto& m :
       {vr::encode_description({}, vr::kSenderDescription, 0, tracker),
        vr::encode_description({}, vr::kTypeDescription, 0, "vrpn_Base text_message"),
        vr::encode_description({}, vr::kTypeDescription, 1, vr::kPingType),
        vr::encode_description({}, vr::kTypeDescription, 2, vr::kPongType),
        vr::encode_message({1'700'000'000, 0}, 0, 1, {})}) {
    out.insert(out.end(), m.begin(), m.end());
  }
  return out;
}

TEST(VrpnEmulator, AnswersAPingFromATrackerWithAPongFromIt) {
  const SimWorld world(still_sim());
  auto server = serve_sim(world);
  RawClient client(server->port());
  ASSERT_TRUE(client.read_until(vr::kPosQuatType, "Body2"));  // Body2 is a tracker by now
  client.send(ping_from("Body2"));
  auto pong = client.read_until(vr::kPongType);
  ASSERT_TRUE(pong) << "no pong among the reports";
  EXPECT_EQ(pong->sender, "Body2");
  EXPECT_EQ(pong->header.payload_bytes(), 0u);
  EXPECT_EQ(server->counters().pongs.load(), 1u);
  // Every ping is answered (the client pings once a second until it hears one).
  client.send(vr::encode_message({1'700'000'001, 0}, 0, 1, {}));
  ASSERT_TRUE(client.read_until(vr::kPongType, "Body2"));
  EXPECT_EQ(server->counters().pongs.load(), 2u);
}

TEST(VrpnEmulator, DoesNotAnswerAPingForATrackerItDoesNotHave) {
  const SimWorld world(still_sim());
  auto server = serve_sim(world);
  RawClient client(server->port());
  ASSERT_TRUE(client.read_until(vr::kPosQuatType, "Body1"));
  client.send(ping_from("Tracker0"));
  client.send(ping_from("Body1"));  // answered: proves the first was read and let pass
  auto pong = client.read_until(vr::kPongType);
  ASSERT_TRUE(pong);
  EXPECT_EQ(pong->sender, "Body1");
  EXPECT_EQ(server->counters().pongs.load(), 1u);
}

/// The Velocity payload (vrpn_Tracker::encode_vel_to): sensor, sensor, vel[3], vel_quat (x, y,
/// z, w), vel_quat_dt, all big-endian.
struct Velocity {
  std::int32_t sensor = -1;
  Eigen::Vector3d v_m_s;
  Eigen::Quaterniond vel_quat;
  double dt_s = 0;
};
Velocity parse_velocity(std::span<const std::byte> payload) {
  EXPECT_EQ(payload.size(), 72u);
  wire::ByteReader r(payload);
  Velocity v;
  v.sensor = *r.read<std::int32_t>(wire::Endian::big);
  (void)r.skip(4);
  std::array<double, 8> x{};
  for (double& d : x) d = *r.read<double>(wire::Endian::big);
  v.v_m_s = Eigen::Vector3d(x[0], x[1], x[2]);
  v.vel_quat = Eigen::Quaterniond(x[6], x[3], x[4], x[5]);
  v.dt_s = x[7];
  return v;
}

// Body2 flies a circle (sim_world.hpp kind 1: r = 1 m, one turn in 8 s, 0.785 m/s). Each
// Velocity follows its Pos_Quat; the frame is found from the (noise-free, exactly transmitted)
// position. The emulator's velocity is the difference over one frame, so it is the sim's
// velocity at the middle of that step (exact for a circle up to (ω·dt)²/24).
TEST(VrpnEmulator, VelocityIsTheSimulatedBodysVelocity) {
  const SimWorld world(still_sim());
  std::map<std::array<double, 3>, std::uint64_t> frame_of;
  for (std::uint64_t n = 1; n <= 40000; ++n) {
    const auto p = world.truth(1, world.time_s(n)).p_world_m;
    frame_of[{p.x(), p.y(), p.z()}] = n;
  }
  auto server = serve_sim(world);
  RawClient client(server->port());
  int checked = 0;
  for (int i = 0; i < 50; ++i) {
    auto pose_msg = client.read_until(vr::kPosQuatType, "Body2");
    ASSERT_TRUE(pose_msg);
    const auto next = client.read();
    ASSERT_EQ(next.type, vr::kVelocityType);
    ASSERT_EQ(next.sender, "Body2");
    auto pose = vr::parse_pos_quat(pose_msg->payload);
    ASSERT_TRUE(pose);
    const auto it =
        frame_of.find({pose.value().p_m.x(), pose.value().p_m.y(), pose.value().p_m.z()});
    ASSERT_NE(it, frame_of.end()) << "a Body2 position the sim never had";
    const Velocity v = parse_velocity(next.payload);
    EXPECT_EQ(v.sensor, 0);
    if (it->second == 1 || i == 0) continue;  // the first report has no step behind it
    const double dt = 1.0 / world.config().rate_hz;
    EXPECT_NEAR(v.dt_s, dt, 1e-9);
    const auto truth = world.truth(1, world.time_s(it->second) - dt / 2);
    EXPECT_GT(v.v_m_s.norm(), 0.5);
    EXPECT_LT((v.v_m_s - truth.v_world_m_s).norm(), 1e-3)
        << "got " << v.v_m_s.transpose() << ", sim " << truth.v_world_m_s.transpose();
    // vel_quat turns the previous attitude into this one over vel_quat_dt.
    const auto before = world.truth(1, world.time_s(it->second) - dt).q_world_body;
    const auto now = world.truth(1, world.time_s(it->second)).q_world_body;
    EXPECT_NEAR(std::abs((v.vel_quat * before).dot(now)), 1.0, 1e-9);
    EXPECT_GT(2 * std::acos(std::min(1.0, std::abs(v.vel_quat.w()))), 1e-3);
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

// A VRPN client named without tcp:// (`Body1@HOST`, as ROS drivers name it) listens on a TCP
// port and sends "HOST PORT" and a NUL over UDP to the server's port (vrpn_udp_request_lob_packet);
// the server calls it back there and the cookie exchange follows as on an accepted connection.
// A request for a port below 1024 or with a bad host is ignored, as VRPN does.
TEST(VrpnEmulator, CallsBackAClientThatAsksOverUdp) {
  const SimWorld world(still_sim());
  auto server = serve_sim(world);
  asio::io_context io;
  tcp::acceptor listener(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  asio::ip::udp::socket lob(io, asio::ip::udp::v4());
  const asio::ip::udp::endpoint to(asio::ip::make_address("127.0.0.1"), server->port());
  for (const std::string bad : {"127.0.0.1 80", "127.0.0.1;x 5000", "garbage"}) {
    lob.send_to(asio::buffer(bad.c_str(), bad.size() + 1), to);
  }
  const std::string request = "127.0.0.1 " + std::to_string(listener.local_endpoint().port());
  lob.send_to(asio::buffer(request.c_str(), request.size() + 1), to);
  tcp::socket called(io);
  bool accepted = false;
  listener.async_accept(called, [&](const asio::error_code& ec) { accepted = !ec; });
  io.run_for(std::chrono::seconds(10));  // returns once called back
  ASSERT_TRUE(accepted) << "the emulator never called back";
  std::array<std::byte, vr::kCookieBytes> cookie{};
  asio::read(called, asio::buffer(cookie));
  const auto theirs = vr::parse_cookie(cookie);
  ASSERT_TRUE(theirs);
  EXPECT_EQ(theirs.value().magic, vr::kMagic);
  EXPECT_EQ(server->counters().bad_lobs.load(), 3u);
  EXPECT_EQ(server->counters().lobs_answered.load(), 1u);
}

}  // namespace
}  // namespace mocaplink::sources

// The endpoint forms that make every mocaplink process the same peer to a vehicle (issue 37;
// docs/config.md "Links"): udp:// with a fixed local port, udpin:// (listen, answer the vehicle's
// address) and tcpin:// (a TCP server for one vehicle connection at a time), over real loopback
// sockets. The vehicle side is a plain socket scripted here; the PX4 that answers only the first
// address that spoke to it (mavlink_receiver latches its partner) is modelled by OnePeerVehicle.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <asio/ip/tcp.hpp>
#include <asio/ip/udp.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>

#include "link_test_support.hpp"
#include "mocaplink/io/link_tcp_in.hpp"
#include "mocaplink/io/link_udp.hpp"
#include "mocaplink/io/link_udp_in.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::io {
namespace {

using test::kHeartbeat;
using test::run_until;
using tcp = asio::ip::tcp;
using udp = asio::ip::udp;

const auto kLoopback = asio::ip::make_address("127.0.0.1");

/// A HEARTBEAT from `sysid` (a ground station is 255).
std::vector<std::uint8_t> heartbeat_from(std::uint8_t sysid) {
  mavlink::Heartbeat hb;
  hb.type = sysid == 255 ? 6 : 2;  // MAV_TYPE_GCS : MAV_TYPE_QUADROTOR
  const auto frame =
      mavlink::encode(hb, mavlink::FrameHeader{.seq = 0, .sysid = sysid, .compid = 1});
  return {frame.bytes().begin(), frame.bytes().end()};
}

/// A free UDP port on loopback (bound, then released).
std::uint16_t free_udp_port(asio::io_context& loop) {
  udp::socket probe(loop, udp::endpoint(kLoopback, 0));
  return probe.local_endpoint().port();
}

/// PX4's UDP link as seen from outside: it answers only the first address that sent it a datagram
/// since it booted, and sends its heartbeat there.
class OnePeerVehicle {
 public:
  explicit OnePeerVehicle(asio::io_context& loop) : socket_(loop, udp::endpoint(kLoopback, 0)) {
    receive();
  }
  [[nodiscard]] std::uint16_t port() const { return socket_.local_endpoint().port(); }
  /// Sends a heartbeat to its partner, if it has one.
  void beat() {
    if (partner_) socket_.send_to(asio::buffer(kHeartbeat), *partner_);
  }
  std::optional<udp::endpoint> partner_;
  std::vector<udp::endpoint> heard_from;

 private:
  void receive() {
    socket_.async_receive_from(asio::buffer(buffer_), from_,
                               [this](const std::error_code& e, std::size_t) {
                                 if (e) return;
                                 heard_from.push_back(from_);
                                 if (!partner_) partner_ = from_;
                                 receive();
                               });
  }
  udp::socket socket_;
  udp::endpoint from_;
  std::array<std::uint8_t, 2048> buffer_{};
};

/// Whether `link`, started, hears `vehicle`'s heartbeats after speaking to it once.
bool hears(asio::io_context& loop, Link& link, OnePeerVehicle& vehicle) {
  std::size_t heard = 0;
  link.start([&](const mavlink::FrameView&, core::HostTime) { ++heard; }, {});
  return run_until(
      loop,
      [&] {
        (void)link.send(kHeartbeat);
        vehicle.beat();
        return heard > 0;
      },
      std::chrono::milliseconds(1500));
}

TEST(UdpLinkBind, EveryProcessOnTheSameLocalPortIsHeardByAOnePeerVehicle) {
  asio::io_context loop;
  OnePeerVehicle vehicle(loop);
  const std::uint16_t local = free_udp_port(loop);
  const config::HostPort bind{"127.0.0.1", local};
  {  // `vehicle setup`: the first process on this boot
    UdpLink first(loop, "127.0.0.1", vehicle.port(), test::options(), bind);
    EXPECT_TRUE(hears(loop, first, vehicle));
    EXPECT_EQ(first.local_endpoint().port(), local);
    EXPECT_EQ(first.url(), "udp://127.0.0.1:" + std::to_string(vehicle.port()) +
                               "?bind=127.0.0.1:" + std::to_string(local));
    first.close(std::chrono::milliseconds(0));
  }
  {  // `run` after it: the same peer, so the vehicle answers it too
    UdpLink second(loop, "127.0.0.1", vehicle.port(), test::options(), bind);
    EXPECT_TRUE(hears(loop, second, vehicle));
  }
  ASSERT_TRUE(vehicle.partner_.has_value());
  EXPECT_EQ(vehicle.partner_->port(), local);
}

TEST(UdpLinkBind, WithoutBindTheSecondProcessIsNotHeard) {
  // The failure the forms exist for (the control of the test above): an ephemeral port per
  // process, and the vehicle keeps answering the first one.
  asio::io_context loop;
  OnePeerVehicle vehicle(loop);
  {
    UdpLink first(loop, "127.0.0.1", vehicle.port(), test::options());
    EXPECT_TRUE(hears(loop, first, vehicle));
    first.close(std::chrono::milliseconds(0));
  }
  UdpLink second(loop, "127.0.0.1", vehicle.port(), test::options());
  EXPECT_FALSE(hears(loop, second, vehicle));
}

TEST(UdpLinkBind, APortOwnedByAnotherSocketLeavesTheLinkDownAndSaysWhy) {
  asio::io_context loop;
  OnePeerVehicle vehicle(loop);
  udp::socket owner(loop, udp::endpoint(kLoopback, 0));
  const config::HostPort bind{"127.0.0.1", owner.local_endpoint().port()};
  UdpLink link(loop, "127.0.0.1", vehicle.port(),
               test::options(std::chrono::milliseconds(10), std::chrono::milliseconds(20)), bind);
  std::string why;
  link.start({}, [&](TransportState, const std::string& detail) { why = detail; });
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::down; }));
  EXPECT_NE(why.find("another mocaplink process"), std::string::npos) << why;
  EXPECT_FALSE(link.send(kHeartbeat));
  // Freed: the retry binds it.
  owner.close();
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up; }));
  EXPECT_TRUE(link.send(kHeartbeat));
}

// udpin://: nothing is sent before the vehicle speaks; then it is answered where it speaks from.
class UdpInTest : public testing::Test {
 protected:
  UdpInTest() {
    LinkOptions o = test::options();
    o.vehicle_system_id = 1;
    link = std::make_unique<UdpInLink>(loop, "127.0.0.1", 0, o);
    link->start([this](const mavlink::FrameView& f, core::HostTime) { sysids.push_back(f.sysid); },
                [this](TransportState s, const std::string& detail) {
                  states.push_back(std::string(to_string(s)) + ": " + detail);
                });
  }
  /// A vehicle socket on loopback sending `bytes` to the link.
  void speak(udp::socket& from, const std::vector<std::uint8_t>& bytes) {
    from.send_to(asio::buffer(bytes), udp::endpoint(kLoopback, link->local_endpoint().port()));
  }
  /// Datagrams that reach `at` within a short wait (after one send from the link).
  std::size_t received_at(udp::socket& at) {
    (void)link->send(kHeartbeat);
    std::size_t n = 0;
    run_until(
        loop,
        [&] {
          std::array<std::uint8_t, 512> buffer{};
          std::error_code ec;
          at.non_blocking(true);
          while (at.receive(asio::buffer(buffer), 0, ec) > 0 && !ec) ++n;
          return n > 0;
        },
        std::chrono::milliseconds(300));
    return n;
  }
  asio::io_context loop;
  std::unique_ptr<UdpInLink> link;
  std::vector<std::uint8_t> sysids;
  std::vector<std::string> states;
};

TEST_F(UdpInTest, SendsNothingBeforeTheVehicleSpeaksThenAnswersItsAddress) {
  EXPECT_EQ(link->state(), TransportState::connecting);
  EXPECT_FALSE(link->send(kHeartbeat));
  EXPECT_EQ(link->counters().dropped_down, 1u);
  EXPECT_EQ(link->counters().frames_sent, 0u);

  udp::socket vehicle(loop, udp::endpoint(kLoopback, 0));
  speak(vehicle, kHeartbeat);
  ASSERT_TRUE(run_until(loop, [&] { return link->state() == TransportState::up; }));
  EXPECT_EQ(link->peer().port(), vehicle.local_endpoint().port());
  EXPECT_EQ(sysids, (std::vector<std::uint8_t>{1}));
  EXPECT_EQ(received_at(vehicle), 1u);
  EXPECT_EQ(link->counters().frames_sent, 1u);
  EXPECT_EQ(link->url(), "udpin://127.0.0.1:0");
  ASSERT_FALSE(states.empty());
  EXPECT_NE(states.back().find("up: the vehicle spoke from 127.0.0.1:" +
                               std::to_string(vehicle.local_endpoint().port())),
            std::string::npos)
      << states.back();
}

TEST_F(UdpInTest, FollowsTheVehicleToANewAddressAndSaysSo) {
  udp::socket before(loop, udp::endpoint(kLoopback, 0));
  speak(before, kHeartbeat);
  ASSERT_TRUE(run_until(loop, [&] { return link->state() == TransportState::up; }));
  // The vehicle rebooted onto another port.
  udp::socket after(loop, udp::endpoint(kLoopback, 0));
  speak(after, kHeartbeat);
  ASSERT_TRUE(
      run_until(loop, [&] { return link->peer().port() == after.local_endpoint().port(); }));
  EXPECT_EQ(received_at(after), 1u);
  EXPECT_EQ(received_at(before), 0u);
  EXPECT_NE(states.back().find("the vehicle now speaks from 127.0.0.1:" +
                               std::to_string(after.local_endpoint().port()) + " (was 127.0.0.1:" +
                               std::to_string(before.local_endpoint().port()) + ")"),
            std::string::npos)
      << states.back();
}

TEST_F(UdpInTest, OtherSystemsAndBadFramesNeverTakeTheVehiclesPoses) {
  udp::socket vehicle(loop, udp::endpoint(kLoopback, 0));
  speak(vehicle, kHeartbeat);
  ASSERT_TRUE(run_until(loop, [&] { return link->state() == TransportState::up; }));
  // A ground station's heartbeat on the same port: delivered, but the link keeps answering the
  // vehicle.
  udp::socket gcs(loop, udp::endpoint(kLoopback, 0));
  speak(gcs, heartbeat_from(255));
  ASSERT_TRUE(run_until(loop, [&] { return sysids.size() == 2; }));
  EXPECT_EQ(sysids.back(), 255);
  // A corrupted frame from yet another address: counted, never followed.
  udp::socket stranger(loop, udp::endpoint(kLoopback, 0));
  auto bad = kHeartbeat;
  bad[14] ^= 0xff;
  speak(stranger, bad);
  ASSERT_TRUE(run_until(loop, [&] { return link->counters().parser.bad_crc == 1; }));
  EXPECT_EQ(link->peer().port(), vehicle.local_endpoint().port());
  EXPECT_EQ(received_at(vehicle), 1u);
  EXPECT_EQ(received_at(gcs), 0u);
  EXPECT_EQ(received_at(stranger), 0u);
}

TEST(UdpInLink, APortAlreadyOwnedIsDownWithTheReasonAndRetried) {
  asio::io_context loop;
  udp::socket owner(loop, udp::endpoint(kLoopback, 0));
  UdpInLink link(loop, "127.0.0.1", owner.local_endpoint().port(),
                 test::options(std::chrono::milliseconds(10), std::chrono::milliseconds(20)));
  std::string why;
  link.start({}, [&](TransportState, const std::string& detail) { why = detail; });
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::down; }));
  EXPECT_NE(why.find("cannot listen on udpin://127.0.0.1:"), std::string::npos) << why;
  owner.close();
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::connecting; }));
  EXPECT_NE(why.find("waiting for the vehicle to speak"), std::string::npos) << why;
}

TEST(TcpInLink, ServesOneVehicleThatDisconnectsAndComesBack) {
  asio::io_context loop;
  TcpInLink link(loop, "127.0.0.1", 0,
                 test::options(std::chrono::milliseconds(5), std::chrono::milliseconds(20)));
  std::vector<std::uint32_t> msgids;
  link.start([&](const mavlink::FrameView& f, core::HostTime) { msgids.push_back(f.msgid); }, {});
  ASSERT_TRUE(run_until(loop, [&] { return link.local_endpoint().port() != 0; }));
  EXPECT_EQ(link.state(), TransportState::connecting);
  EXPECT_FALSE(link.send(kHeartbeat));  // nobody connected yet
  const tcp::endpoint server(kLoopback, link.local_endpoint().port());

  for (int round = 1; round <= 2; ++round) {
    tcp::socket vehicle(loop);
    vehicle.connect(server);
    ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up; })) << round;
    ASSERT_TRUE(link.send(kHeartbeat));
    std::vector<std::uint8_t> got(kHeartbeat.size());
    ASSERT_TRUE(run_until(loop, [&] { return link.counters().frames_sent == std::size_t(round); }));
    asio::read(vehicle, asio::buffer(got));
    EXPECT_EQ(got, kHeartbeat);
    asio::write(vehicle, asio::buffer(kHeartbeat));
    ASSERT_TRUE(run_until(loop, [&] { return msgids.size() == std::size_t(round); }));
    vehicle.close();  // the vehicle goes away
    ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::down; })) << round;
  }
  EXPECT_EQ(link.counters().connects, 2u);
}

TEST(TcpInLink, ANewConnectionReplacesAHalfOpenOne) {
  asio::io_context loop;
  TcpInLink link(loop, "127.0.0.1", 0, test::options());
  std::vector<std::string> states;
  link.start({}, [&](TransportState s, const std::string& detail) {
    states.push_back(std::string(to_string(s)) + ": " + detail);
  });
  ASSERT_TRUE(run_until(loop, [&] { return link.local_endpoint().port() != 0; }));
  const tcp::endpoint server(kLoopback, link.local_endpoint().port());
  tcp::socket old_connection(loop);
  old_connection.connect(server);
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up; }));
  // The vehicle rebooted: its old connection is never closed, a new one arrives.
  tcp::socket fresh(loop);
  fresh.connect(server);
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().connects == 2; }));
  EXPECT_EQ(link.state(), TransportState::up);
  ASSERT_TRUE(link.send(kHeartbeat));
  std::vector<std::uint8_t> got(kHeartbeat.size());
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().frames_sent == 1; }));
  asio::read(fresh, asio::buffer(got));
  EXPECT_EQ(got, kHeartbeat);
  // The old one was closed by the link: its next read ends.
  std::error_code ec;
  std::array<std::uint8_t, 16> buffer{};
  (void)old_connection.read_some(asio::buffer(buffer), ec);
  EXPECT_EQ(ec, asio::error::eof);
  bool said = false;
  for (const auto& s : states) said = said || s.find("connected again from") != std::string::npos;
  EXPECT_TRUE(said) << testing::PrintToString(states);
  link.close(std::chrono::milliseconds(0));
  // Closed for good: the port can be listened on again (SO_REUSEADDR, as the link itself sets
  // it: the closed connections may linger in TIME_WAIT, the listener must not).
  tcp::acceptor again(loop);
  again.open(tcp::v4());
  again.set_option(tcp::acceptor::reuse_address(true));
  std::error_code bind_error;
  again.bind(server, bind_error);
  EXPECT_FALSE(bind_error) << bind_error.message();
}

}  // namespace
}  // namespace mocaplink::io

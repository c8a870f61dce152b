// natnet:// against a hostile server: a raw UDP socket on 127.0.0.1 that answers NAT_CONNECT and
// NAT_REQUEST_MODELDEF itself (bytes from the codecs, checked against natnet.md §9 in
// tests/libs/wire) and then sends short datagrams, lying headers, truncated frames, absurd counts
// and trailing bytes between valid frames, repeats a frame, names an unknown id, and finally
// announces an unsupported bitstream. The client must count each fault, never crash, deliver
// every valid frame once, and refuse version 5.0 with a clear message.
#include <asio.hpp>
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/natnet_source.hpp"
#include "mocaplink/wire/natnet_packet.hpp"

namespace mocaplink::sources {
namespace {

namespace nn = wire::natnet;
using asio::ip::udp;
using Bytes = std::vector<std::byte>;

Bytes frame(std::int32_t number, std::vector<std::int32_t> ids = {7}) {
  nn::FrameOfData f;
  f.frame_number = number;
  for (const std::int32_t id : ids) {
    nn::RigidBodySample rb;
    rb.id = id;
    rb.position = {1.0f, 2.0f, 3.0f};
    rb.params = 1;
    f.rigid_bodies.push_back(rb);
  }
  f.mid_exposure_ticks = 1000;
  f.transmit_ticks = 1500;
  return nn::encode_frame(f, {3, 0});
}

class HostileServer {
 public:
  explicit HostileServer(nn::Version version) : version_(version) {
    thread_ = std::thread([this] { run(); });
  }
  ~HostileServer() {
    stop_ = true;
    // Wake the blocking receive (closing the socket would not, on Linux).
    asio::error_code ignored;
    udp::socket waker(io_, udp::v4());
    waker.send_to(asio::buffer("x", 1), socket_.local_endpoint(), 0, ignored);
    if (thread_.joinable()) thread_.join();
  }
  std::uint16_t port() const { return port_; }
  std::atomic<int> model_requests{0};

 private:
  void run() {
    char buf[2048];
    udp::endpoint from;
    while (!stop_) {
      asio::error_code ec;
      const std::size_t n = socket_.receive_from(asio::buffer(buf), from, 0, ec);
      if (ec) return;
      if (n < 4) continue;
      const auto id = static_cast<std::uint8_t>(buf[0]);
      if (id == 0) {
        nn::ServerInfo info;
        info.sender.name = "Hostile";
        info.sender.natnet_version = {version_.major, version_.minor, 0, 0};
        info.has_connection_info = true;
        info.clock_hz = 1000;
        info.multicast = false;
        send(nn::encode_server_info(info), from);
      } else if (id == 4) {
        ++model_requests;
        nn::ModelDefinitions defs;
        nn::RigidBodyDescription rb;
        rb.name = "Quad";
        rb.id = 7;
        defs.rigid_bodies.push_back(rb);
        send(nn::encode_model_definitions(defs, version_), from);
        if (model_requests > 1) continue;
        // Once the client knows the models: the faults, each between valid frames.
        send(frame(1), from);
        send(Bytes{std::byte{7}}, from);  // shorter than a header
        send(Bytes{std::byte{7}, std::byte{0}, std::byte{0xff}, std::byte{0xff}}, from);  // lies
        Bytes truncated = frame(2);
        truncated.resize(truncated.size() - 3);
        truncated[2] = static_cast<std::byte>(truncated.size() - 4);
        send(truncated, from);
        Bytes absurd = frame(3);
        absurd[4 + 12] = std::byte{0xff};  // rigid-body count 255 in 38 bytes
        absurd[4 + 13] = std::byte{0xff};
        send(absurd, from);
        send(frame(4), from);
        send(frame(4), from);  // repeated
        Bytes trailing = frame(5);
        trailing.push_back(std::byte{0});
        send(trailing, from);           // accepted, trailing byte counted
        send(frame(6, {7, 99}), from);  // unknown id 99: dropped, models re-requested
      }
    }
  }
  void send(const Bytes& b, const udp::endpoint& to) {
    asio::error_code ignored;
    socket_.send_to(asio::buffer(b), to, 0, ignored);
  }

  nn::Version version_;
  asio::io_context io_;
  udp::socket socket_{io_, udp::endpoint(asio::ip::address_v4::loopback(), 0)};
  std::uint16_t port_ = socket_.local_endpoint().port();
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

NatnetSourceOptions options(std::uint16_t port) {
  NatnetSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.command_port = port;
  o.target.local = "127.0.0.1";
  o.target.transport = NatnetTransport::unicast;
  o.target.data_port = 1;  // not bindable without privileges: frames on the command socket
  o.connect_retry = std::chrono::milliseconds(50);
  o.retry = core::RetryPolicy{std::chrono::milliseconds(20), std::chrono::milliseconds(20),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(5000)};
  o.model_retry = std::chrono::milliseconds(0);  // frames arrive in a burst here
  return o;
}

TEST(NatnetHostileServer, FaultsAreCountedAndValidFramesDeliveredOnce) {
  HostileServer server({3, 0});
  NatnetSource client(options(server.port()), "natnet://hostile");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  // Frames 1, 4, 5 and 6 (without its unknown body) are valid.
  ASSERT_TRUE(got.wait([](const std::vector<test::Event>& events) {
    for (const auto& e : events) {
      if (e.is_frame && e.frame.frame_number == 6) return true;
    }
    return false;
  })) << client.last_error();
  // The unknown id makes the client ask for the model definitions again (polled: the server's
  // counter wakes no one; the bound only stops a hang).
  for (int i = 0; i < 1000 && server.model_requests.load() < 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GE(server.model_requests.load(), 2);
  client.stop();
  std::vector<std::uint64_t> numbers;
  for (const auto& e : got.events()) {
    if (!e.is_frame) continue;
    numbers.push_back(e.frame.frame_number);
    ASSERT_EQ(e.frame.bodies.size(), 1u);
    EXPECT_EQ(e.frame.bodies[0].name, "Quad");
    EXPECT_TRUE(e.frame.bodies[0].p_world_m.isApprox(Eigen::Vector3d(1, 2, 3)));
    EXPECT_EQ(e.frame.source_latency->count(), 500'000'000);  // 500 ticks at 1 kHz
  }
  // Strictly increasing: frame 4's repeat was not delivered.
  for (std::size_t i = 1; i < numbers.size(); ++i) EXPECT_GT(numbers[i], numbers[i - 1]);
  EXPECT_GE(client.counters().malformed.load(), 4u);  // short, lying, truncated, absurd
  EXPECT_GE(client.natnet_counters().duplicate_frames.load(), 1u);
  EXPECT_GE(client.natnet_counters().trailing_bytes.load(), 1u);
  EXPECT_GE(client.natnet_counters().unknown_ids.load(), 1u);
}

TEST(NatnetHostileServer, AnUnsupportedBitstreamIsRefusedClearly) {
  HostileServer server({5, 0});
  NatnetSource client(options(server.port()), "natnet://hostile");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait([](const std::vector<test::Event>& events) {
    for (const auto& e : events) {
      if (!e.is_frame && e.state == SourceState::disconnected) return true;
    }
    return false;
  }));
  client.stop();
  EXPECT_NE(client.last_error().find("bitstream 5.0"), std::string::npos) << client.last_error();
  EXPECT_EQ(test::Collector::frame_count(got.events()), 0u);
}

}  // namespace
}  // namespace mocaplink::sources

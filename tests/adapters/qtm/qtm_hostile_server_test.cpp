// qtm:// client against a scripted hostile server on 127.0.0.1 (blocking sockets on a thread):
// versions refused until 1.18, a malformed data packet and malformed XML (counted, connection
// kept), a body count that no longer matches the names (re-read), "Parameters not available"
// (retried), an impossible packet size (counted, connection dropped, reconnect with no stale
// pose), and a server that refuses with an error packet.
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <asio.hpp>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/qtm_source.hpp"
#include "mocaplink/wire/qtm_frame.hpp"
#include "mocaplink/wire/qtm_parameters.hpp"

namespace mocaplink::sources {
namespace {

using asio::ip::tcp;
using test::Collector;
using test::Event;
namespace wq = wire::qtm;

struct Packet {
  std::uint32_t type = 0;
  std::string text;
};

Packet read_packet(tcp::socket& s) {
  std::array<std::byte, 8> header{};
  asio::read(s, asio::buffer(header));
  const auto h = wq::parse_header(header, 1 << 20);
  if (!h) throw std::runtime_error("bad header from the client");
  std::vector<std::byte> payload(h.value().size - 8);
  asio::read(s, asio::buffer(payload));
  return {h.value().type, wq::text_of(payload)};
}

// Reads packets until a command starting with `prefix`; returns its text.
std::string expect_command(tcp::socket& s, const std::string& prefix) {
  for (;;) {
    const Packet p = read_packet(s);
    if (p.type == 1 && p.text.starts_with(prefix)) return p.text;
  }
}

void send(tcp::socket& s, const std::vector<std::byte>& bytes) {
  asio::write(s, asio::buffer(bytes));
}

void send_text(tcp::socket& s, wq::PacketType type, const std::string& text) {
  send(s, wq::encode_text(type, text));
}

std::vector<std::byte> data(std::uint32_t frame_number, std::size_t bodies, float x_mm) {
  wq::DataPacket d;
  d.frame_number = frame_number;
  d.timestamp_us = 1000 * frame_number;
  wq::SixDof six;
  for (std::size_t i = 0; i < bodies; ++i) {
    wq::Body6d b;
    b.position_mm = {x_mm, 0, 0};
    b.rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    six.bodies.push_back(b);
  }
  d.six_dof = {six};
  return wq::encode_data(d);
}

TEST(QtmHostileServer, CountsEveryFaultReconnectsAndStillDecodes) {
  asio::io_context io;
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  const auto port = acceptor.local_endpoint().port();
  std::atomic<int> stage{0};
  std::string failure;
  std::thread server([&] {
    try {
      const std::vector<std::string> one = {"Drone"};
      {  // Connection 1.
        tcp::socket s = acceptor.accept();
        send(s, wq::encode_text(wq::PacketType::command, wq::kWelcome));
        // Refuse every version above 1.18, once with an error packet.
        for (int minor = 28; minor > 18; --minor) {
          if (expect_command(s, "Version ") != "Version 1." + std::to_string(minor)) {
            throw std::runtime_error("versions not tried newest first");
          }
          if (minor == 25) {
            send_text(s, wq::PacketType::error, "Parse Error");
          } else {
            send_text(s, wq::PacketType::command, "Version NOT supported");
          }
        }
        expect_command(s, "Version 1.18");
        send_text(s, wq::PacketType::command, "Version set to 1.18");
        expect_command(s, "GetParameters");
        send_text(s, wq::PacketType::command, "Parameters not available");
        expect_command(s, "GetParameters");  // retried
        send_text(s, wq::PacketType::xml, "<QTM_Parameters_Ver_1.18><The_6D><Bodies>2");
        expect_command(s, "GetParameters");  // malformed XML: retried
        send_text(s, wq::PacketType::xml, wq::encode_parameters(one, 18, {true, true}, 100));
        expect_command(s, "StreamFrames AllFrames 6D");
        send(s, data(1, 1, 1000));
        // Malformed data: a 6D component claiming more bodies than its bytes hold.
        auto bad = data(2, 1, 1000);
        bad[32] = std::byte{9};
        send(s, bad);
        send(s, data(3, 2, 1000));  // two bodies, one name: re-read
        expect_command(s, "GetParameters");
        send(s, wq::encode_event(11));
        send_text(s, wq::PacketType::xml, wq::encode_parameters(one, 18, {true, true}, 100));
        send(s, data(4, 1, 1000));
        stage = 1;
        while (stage == 1) std::this_thread::yield();
        // An impossible size: the framing is lost, the connection must go.
        const std::array<std::byte, 8> broken{std::byte{3}, {}, {}, {}, std::byte{3}, {}, {}, {}};
        send(s, std::vector<std::byte>(broken.begin(), broken.end()));
        asio::error_code ec;
        std::array<std::byte, 64> sink{};
        while (!ec) s.read_some(asio::buffer(sink), ec);  // until the client closes
      }
      {  // Connection 2: refused like a full QTM.
        tcp::socket s = acceptor.accept();
        send_text(s, wq::PacketType::error, std::string(wq::kMaxClientsError));
      }
      {  // Connection 3: fine again, another position.
        tcp::socket s = acceptor.accept();
        send(s, wq::encode_text(wq::PacketType::command, wq::kWelcome, false));  // no NUL
        expect_command(s, "Version 1.28");
        send_text(s, wq::PacketType::command, "Version set to 1.28");
        expect_command(s, "GetParameters");
        send_text(s, wq::PacketType::xml, wq::encode_parameters(one, 28, {true, true}, 100));
        expect_command(s, "StreamFrames");
        for (std::uint32_t n = 10; n < 15; ++n) send(s, data(n, 1, 2000));
        while (stage != 4) std::this_thread::yield();
      }
    } catch (const std::exception& e) {
      failure = e.what();
      stage = 99;
    }
  });

  QtmSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.port = port;
  o.retry = core::RetryPolicy{std::chrono::milliseconds(10), std::chrono::milliseconds(10),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(20)};
  o.parameters_retry = std::chrono::milliseconds(10);
  QtmSource source(o, "qtm://hostile");
  Collector got;
  source.start(got.frame_sink(), got.state_sink());
  const auto frames_at_least = [&](std::size_t n) { return got.wait_frames(n) && stage != 99; };
  ASSERT_TRUE(frames_at_least(2)) << failure;
  while (stage == 0) std::this_thread::yield();
  stage = 2;
  ASSERT_TRUE(got.wait([](const std::vector<Event>& events) {
    std::size_t n = 0;
    for (const auto& e : events) n += e.is_frame && e.frame.bodies[0].p_world_m.x() == 2.0;
    return n >= 5;
  })) << failure;
  stage = 4;
  server.join();
  source.stop();
  ASSERT_EQ(failure, "");

  std::vector<std::uint64_t> numbers;
  bool disconnected = false;
  for (const auto& e : got.events()) {
    if (!e.is_frame) {
      disconnected = disconnected || e.state == SourceState::disconnected;
      continue;
    }
    numbers.push_back(e.frame.frame_number);
    ASSERT_EQ(e.frame.bodies.size(), 1u);
    EXPECT_EQ(e.frame.bodies[0].name, "Drone");
    EXPECT_EQ(e.frame.bodies[0].p_world_m.x(), disconnected ? 2.0 : 1.0);
  }
  EXPECT_EQ(numbers, (std::vector<std::uint64_t>{1, 4, 10, 11, 12, 13, 14}));
  // Malformed: the XML, the data packet and the impossible size.
  EXPECT_EQ(source.counters().malformed, 3u);
  EXPECT_EQ(source.qtm_counters().body_count_changes, 1u);
  EXPECT_GE(source.counters().reconnects, 2u);
  EXPECT_GE(source.qtm_counters().server_errors, 2u);
}

}  // namespace
}  // namespace mocaplink::sources

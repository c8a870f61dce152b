// vicon:// against a hostile server: raw TCP on 127.0.0.1 that sends, one connection after the
// other, a truncated packet, absurd length fields, a wrong tag and malformed items, then unknown
// item types around a valid frame. The client must count each fault, drop that connection,
// reconnect, never crash, never allocate what a length field claims, and still decode the frame.
#include <asio.hpp>
#include <thread>

#include <gtest/gtest.h>

#include "mocaplink/sources/vicon_source.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "vicon_test_support.hpp"

namespace mocaplink::sources {
namespace {

namespace vw = wire::vicon;
using asio::ip::tcp;
using Bytes = std::vector<std::byte>;

Bytes greeting() {
  vw::PacketBuilder b;
  b.add(vw::ObjectEnums{{1, 2, 5, 9, 100004}});
  return b.finish();
}

Bytes raw(std::initializer_list<std::uint32_t> words) {
  Bytes out;
  vw::codec::Writer w(out);
  for (auto v : words) w.put(v);
  return out;
}

Bytes concat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Bytes valid_frame() {
  vw::PacketBuilder b;
  b.add_raw(12345, raw({0xdeadbeef}));  // unknown type: skipped (§3)
  b.add(vw::KeepAlive{});
  b.add(vw::Contents{});
  b.add(vw::StreamInfo{1'350'000});
  b.add(vw::SubjectInfo{7, "Quad1", {vw::SegmentInfo{0, 3, {}, "Quad1"}}, {}, {}});
  b.add(vw::FrameInfo{99});
  b.add(vw::GlobalSegments{7, {vw::SegmentPose{3, {1500, -20, 800}, {1, 0, 0, 0, 1, 0, 0, 0, 1}}}});
  b.add_raw(65001, raw({1, 2, 3}));  // a camera type we never asked for: skipped
  return b.finish();
}

struct Script {
  Bytes bytes;
  bool close_after_write;  // true: close after the client's handshake; false: wait for its close
};

// What our client sends after a greeting offering {1, 2, 5, 9, 100004}: ObjectEnums with those five
// types (8 + 8 + 4 + 5 × 4 bytes) and RequestFrame(1) (17 bytes). Reading them before closing
// means the close is a clean FIN, not a reset that could race the client's read.
constexpr std::size_t kHandshakeBytes = 40 + 17;

// Serves one script per accepted connection, in order, on its own thread.
class HostileServer {
 public:
  explicit HostileServer(std::vector<Script> scripts)
      : acceptor_(io_, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)),
        scripts_(std::move(scripts)),
        thread_([this] { run(); }) {}
  ~HostileServer() {
    asio::error_code ignored;
    acceptor_.close(ignored);
    thread_.join();
  }
  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }

 private:
  void run() {
    for (const Script& s : scripts_) {
      asio::error_code ec;
      tcp::socket socket(io_);
      acceptor_.accept(socket, ec);
      if (ec) return;
      asio::write(socket, asio::buffer(s.bytes), ec);
      if (s.close_after_write) {
        std::array<char, kHandshakeBytes> handshake{};
        asio::read(socket, asio::buffer(handshake), ec);
      } else {
        std::array<char, 256> sink{};
        while (!ec) socket.read_some(asio::buffer(sink), ec);  // until the client closes
      }
      socket.close(ec);
    }
  }

  asio::io_context io_;
  tcp::acceptor acceptor_;
  std::vector<Script> scripts_;
  std::thread thread_;
};

TEST(ViconHostileServer, CountsEveryFaultReconnectsAndStillDecodes) {
  std::vector<Script> scripts;
  // 1. Truncated: a header announcing 100 bytes, 10 sent, connection closed.
  scripts.push_back({concat({greeting(), raw({vw::kPacketTag, 100}), Bytes(10)}), true});
  // 2. Absurd body length (4 GiB − 16): rejected from the header, nothing allocated.
  scripts.push_back({concat({greeting(), raw({vw::kPacketTag, 0xFFFFFFF0})}), false});
  // 3. Wrong packet tag.
  scripts.push_back({concat({greeting(), raw({0x12345678, 0})}), false});
  // 4. An item whose payload length runs past the packet.
  scripts.push_back({concat({greeting(), raw({vw::kPacketTag, 12, 5, 0x7FFFFFFF, 41})}), false});
  // 5. SubjectInfo with a name length of 2^32 − 1 inside a small, well-framed packet.
  scripts.push_back({concat({greeting(), raw({vw::kPacketTag, 16, 2, 8, 1, 0xFFFFFFFF})}), false});
  // 6. A greeting without ObjectEnums.
  scripts.push_back({raw({vw::kPacketTag, 12, 5, 4, 41}), false});
  // 7. Finally a valid frame wrapped in unknown item types and a KeepAlive.
  scripts.push_back({concat({greeting(), valid_frame()}), false});
  HostileServer server(std::move(scripts));

  ViconSourceOptions o;
  o.target = ViconOptions{"127.0.0.1", server.port(), vw::StreamMode::server_push};
  o.retry = core::RetryPolicy{std::chrono::milliseconds(10), std::chrono::milliseconds(10),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(40)};
  o.max_body_bytes = 1024 * 1024;
  ViconSource client(o, "vicon://hostile");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(1));
  const std::string last_error = client.last_error();
  client.stop();

  EXPECT_EQ(client.counters().malformed.load(), 6u) << last_error;
  EXPECT_EQ(client.counters().frames.load(), 1u);
  EXPECT_GE(client.counters().reconnects.load(), 6u);
  EXPECT_EQ(client.vicon_counters().unknown_items.load(), 2u);
  EXPECT_EQ(client.vicon_counters().keep_alives.load(), 1u);

  std::vector<std::string> reasons;
  core::MocapFrame frame;
  for (const auto& e : got.events()) {
    if (e.is_frame) frame = e.frame;
    if (!e.is_frame && e.state == SourceState::disconnected) reasons.push_back(e.detail);
  }
  ASSERT_EQ(reasons.size(), 6u);
  EXPECT_NE(reasons[0].find("closed in the middle of a packet"), std::string::npos) << reasons[0];
  EXPECT_NE(reasons[1].find("exceeds the cap"), std::string::npos) << reasons[1];
  EXPECT_NE(reasons[2].find("bad packet tag"), std::string::npos) << reasons[2];
  EXPECT_NE(reasons[3].find("runs past the packet end"), std::string::npos) << reasons[3];
  EXPECT_NE(reasons[4].find("SubjectInfo"), std::string::npos) << reasons[4];
  EXPECT_NE(reasons[5].find("no ObjectEnums"), std::string::npos) << reasons[5];

  EXPECT_EQ(frame.frame_number, 99u);
  ASSERT_EQ(frame.bodies.size(), 1u);
  EXPECT_EQ(frame.bodies[0].name, "Quad1");
  EXPECT_TRUE(frame.bodies[0].tracked);
  EXPECT_NEAR(frame.bodies[0].p_world_m.x(), 1.5, 1e-12);
  EXPECT_NEAR(frame.bodies[0].p_world_m.y(), -0.02, 1e-12);
  EXPECT_NEAR(frame.bodies[0].q_world_body.w(), 1.0, 1e-12);
}

}  // namespace
}  // namespace mocaplink::sources

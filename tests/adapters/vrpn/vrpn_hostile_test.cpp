// A hostile VRPN server (raw asio on 127.0.0.1 writing chosen bytes) against the vrpn:// client,
// and a hostile client against the emulator: malformed bytes are counted, the connection dropped
// and retried, memory bounded by the caps; never a crash or a frame from bad bytes.
#include <array>
#include <thread>

#include <gtest/gtest.h>
#include <asio.hpp>

#include "../vicon/vicon_test_support.hpp"
#include "mocaplink/sources/vrpn_server.hpp"
#include "mocaplink/sources/vrpn_source.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::sources {
namespace {

namespace vr = wire::vrpn;
using asio::ip::tcp;

/// Accepts connections on 127.0.0.1 and writes `script` to each, then holds it open until the
/// peer closes. Counts connections.
class ScriptedServer {
 public:
  explicit ScriptedServer(std::vector<std::byte> script) : script_(std::move(script)) {
    acceptor_.open(tcp::v4());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    acceptor_.listen();
    accept();
    thread_ = std::thread([this] { io_.run(); });
  }
  ~ScriptedServer() {
    io_.stop();
    thread_.join();
  }
  std::uint16_t port() const { return acceptor_.local_endpoint().port(); }
  int connections() const { return connections_; }

 private:
  void accept() {
    acceptor_.async_accept([this](const asio::error_code& ec, tcp::socket s) {
      if (ec) return;
      ++connections_;
      auto socket = std::make_shared<tcp::socket>(std::move(s));
      asio::async_write(*socket, asio::buffer(script_),
                        [socket](const asio::error_code&, std::size_t) {
                          auto sink = std::make_shared<std::array<char, 256>>();
                          drain(socket, sink);
                        });
      accept();
    });
  }
  static void drain(const std::shared_ptr<tcp::socket>& s,
                    const std::shared_ptr<std::array<char, 256>>& sink) {
    s->async_read_some(asio::buffer(*sink), [s, sink](const asio::error_code& ec, std::size_t) {
      if (!ec) drain(s, sink);
    });
  }

  std::vector<std::byte> script_;
  asio::io_context io_;
  tcp::acceptor acceptor_{io_};
  std::thread thread_;
  std::atomic<int> connections_{0};
};

std::vector<std::byte> cookie_then(std::vector<std::byte> rest) {
  const auto cookie = vr::make_cookie('0');
  rest.insert(rest.begin(), cookie.begin(), cookie.end());
  return rest;
}

std::vector<std::byte> header(std::uint32_t length) {
  std::vector<std::byte> h(vr::kHeaderBytes, std::byte{0});
  for (int i = 0; i < 4; ++i)
    h[static_cast<std::size_t>(i)] = std::byte((length >> (24 - 8 * i)) & 0xFF);
  return h;
}

/// Runs a client against `script` until it counted `malformed` bad connections and reconnected.
void expect_refused(const std::vector<std::byte>& script, const char* what) {
  ScriptedServer server(script);
  VrpnSourceOptions o;
  o.target.host = "127.0.0.1";
  o.target.port = server.port();
  o.retry = core::RetryPolicy{std::chrono::milliseconds(10), std::chrono::milliseconds(10),
                              std::chrono::milliseconds(0), std::chrono::milliseconds(20)};
  VrpnSource client(o, "vrpn://hostile");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  // Each refusal reports `disconnected` (an event) after counting: wait on the counter.
  ASSERT_TRUE(got.wait([&](const std::vector<test::Event>&) {
    return client.counters().malformed >= 2;
  })) << what;
  client.stop();
  EXPECT_EQ(test::Collector::frame_count(got.events()), 0u) << what;
  EXPECT_GE(server.connections(), 2) << what << ": not retried";
  EXPECT_FALSE(client.last_error().empty());
}

TEST(VrpnHostileServer, BadCookie) {
  std::string http = "HTTP/1.1 200 OK\r\nServer: x\r\n\r\n";
  std::vector<std::byte> bytes;
  for (char c : http) bytes.push_back(static_cast<std::byte>(c));
  expect_refused(bytes, "not VRPN");
  auto old = vr::make_cookie('0');
  old[12] = std::byte{'6'};  // major 06
  expect_refused(std::vector<std::byte>(old.begin(), old.end()), "major version 06");
}

TEST(VrpnHostileServer, BadLengths) {
  expect_refused(cookie_then(header(16)), "length < 24");
  expect_refused(cookie_then(header(0x7FFFFFFFu)), "2 GiB message");
}

TEST(VrpnHostileServer, BadDescriptionAndPosQuat) {
  // A sender description whose L overruns its payload.
  auto bad = vr::encode_description({}, vr::kSenderDescription, 0, "Drone1");
  bad[27] = std::byte{60};
  expect_refused(cookie_then(bad), "description length");
  // A described tracker whose Pos_Quat carries a NaN.
  auto script = vr::encode_description({}, vr::kSenderDescription, 0, "Drone1");
  const auto type = vr::encode_description({}, vr::kTypeDescription, 1, vr::kPosQuatType);
  script.insert(script.end(), type.begin(), type.end());
  auto payload = vr::encode_pos_quat(vr::PosQuat{});
  payload[8] = std::byte{0x7f};
  payload[9] = std::byte{0xf8};
  const auto report = vr::encode_message({}, 0, 1, payload);
  script.insert(script.end(), report.begin(), report.end());
  expect_refused(cookie_then(script), "NaN position");
}

TEST(VrpnHostileClient, BadCookieIsClosedAndCounted) {
  VrpnServerOptions o;
  o.listen_host = "127.0.0.1";
  o.port = 0;
  VrpnServer server(o);
  ASSERT_FALSE(server.start({}).has_value());
  asio::io_context io;
  tcp::socket s(io);
  s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), server.port()));
  std::array<std::byte, 24> theirs{};
  asio::read(s, asio::buffer(theirs));
  EXPECT_TRUE(vr::parse_cookie(theirs));  // the emulator speaks first, a real cookie
  const std::string junk = "GET / HTTP/1.0\r\n\r\nxxxxxx";
  asio::write(s, asio::buffer(junk.data(), 24));
  std::array<char, 64> rest{};
  asio::error_code ec;
  while (!ec) (void)s.read_some(asio::buffer(rest), ec);  // the server closes: EOF
  EXPECT_EQ(ec, asio::error::eof);
  server.stop();
  EXPECT_EQ(server.counters().bad_cookies, 1u);
}

}  // namespace
}  // namespace mocaplink::sources

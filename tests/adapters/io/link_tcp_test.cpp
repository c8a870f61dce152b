#include "mocaplink/io/link_tcp.hpp"

#include <array>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>

#include "link_test_support.hpp"

namespace mocaplink::io {
namespace {

using test::kHeartbeat;
using test::run_until;
using tcp = asio::ip::tcp;

TEST(TcpLink, ReconnectsAfterTheServerClosesAndDropsFramesWhileDown) {
  asio::io_context loop;
  tcp::acceptor acceptor(loop, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  std::unique_ptr<tcp::socket> server;
  auto accept = [&] {
    server.reset();
    acceptor.async_accept([&](const std::error_code& e, tcp::socket s) {
      if (!e) server = std::make_unique<tcp::socket>(std::move(s));
    });
  };
  accept();
  TcpLink link(loop, "127.0.0.1", acceptor.local_endpoint().port(),
               test::options(std::chrono::milliseconds(5), std::chrono::milliseconds(20)));
  std::vector<std::uint32_t> msgids;
  link.start([&](const mavlink::FrameView& f, core::HostTime) { msgids.push_back(f.msgid); }, {});
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up && server; }));

  // Out: two frames arrive byte-exact, in order.
  ASSERT_TRUE(link.send(kHeartbeat));
  ASSERT_TRUE(link.send(kHeartbeat));
  // The link writes asynchronously: let the loop run before blocking on the server side.
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().frames_sent == 2; }));
  std::vector<std::uint8_t> got(2 * kHeartbeat.size());
  asio::read(*server, asio::buffer(got));
  EXPECT_TRUE(std::equal(kHeartbeat.begin(), kHeartbeat.end(), got.begin()));
  // In: a frame split over two writes is reassembled.
  asio::write(*server, asio::buffer(kHeartbeat.data(), 5));
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().bytes_received == 5; }));
  asio::write(*server, asio::buffer(kHeartbeat.data() + 5, kHeartbeat.size() - 5));
  ASSERT_TRUE(run_until(loop, [&] { return msgids.size() == 1; }));

  // The server goes away: the link goes down, drops frames, and reconnects when it can.
  accept();
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::down; }));
  EXPECT_FALSE(link.send(kHeartbeat));
  EXPECT_GE(link.counters().dropped_down, 1u);
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up && server; }));
  EXPECT_EQ(link.counters().connects, 2u);
  ASSERT_TRUE(link.send(kHeartbeat));
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().frames_sent == 3; }));
  std::vector<std::uint8_t> again(kHeartbeat.size());
  asio::read(*server, asio::buffer(again));
  EXPECT_EQ(again, kHeartbeat);

  link.close(std::chrono::milliseconds(100));
  EXPECT_EQ(link.state(), TransportState::closed);
}

TEST(TcpLink, RefusedConnectionsAreRetried) {
  asio::io_context loop;
  std::uint16_t port = 0;
  {
    tcp::acceptor probe(loop, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    port = probe.local_endpoint().port();
  }
  TcpLink link(loop, "127.0.0.1", port,
               test::options(std::chrono::milliseconds(5), std::chrono::milliseconds(10)));
  link.start({}, {});
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().refused >= 2; }));
  EXPECT_EQ(link.state(), TransportState::down);
  EXPECT_FALSE(link.send(kHeartbeat));
}

}  // namespace
}  // namespace mocaplink::io

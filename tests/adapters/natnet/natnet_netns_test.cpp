// Multicast for real, as a lab uses it: Motive's defaults (group 239.255.42.99, data port 1511,
// command port 1510), the client joining on the default interface (no ?local=) and the emulator
// sending without a chosen interface, so the kernel's multicast routing decides. Run inside a
// network namespace of its own (netns_run.sh: `unshare -n`, loopback up with MULTICAST and a
// 224.0.0.0/4 route), which needs root; otherwise the test is skipped with the reason.
#include <cstdlib>

#include <gtest/gtest.h>

#include "natnet_test_support.hpp"

namespace mocaplink::sources {
namespace {

TEST(NatnetNetns, MulticastWithMotiveDefaultsOnTheDefaultInterface) {
  const char* inside = std::getenv("MOCAPLINK_NATNET_NETNS");
  if (inside == nullptr || std::string(inside) != "1") {
    GTEST_SKIP() << "needs its own network namespace (run by netns_run.sh as root): "
                 << (inside != nullptr ? inside : "not started by netns_run.sh");
  }
  NatnetServerOptions so;
  so.listen_host = "127.0.0.1";  // defaults otherwise: 1510, multicast, 239.255.42.99:1511
  auto server = test::start_natnet_server(so);
  ASSERT_EQ(server->port(), 1510);
  NatnetSourceOptions co;
  co.target.host = "127.0.0.1";  // natnet://127.0.0.1: everything else from the server info
  co.retry = core::RetryPolicy{std::chrono::milliseconds(20), std::chrono::milliseconds(20),
                               std::chrono::milliseconds(0), std::chrono::milliseconds(5000)};
  NatnetSource client(co, "natnet://127.0.0.1");
  test::Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(30)) << client.last_error();
  client.stop();
  server->stop();
  for (const auto& e : got.events()) {
    if (e.is_frame) test::expect_natnet_matches(e.frame, 0.0, true);
    if (!e.is_frame && e.state == SourceState::connected) {
      EXPECT_NE(e.detail.find("multicast 239.255.42.99:1511"), std::string::npos) << e.detail;
    }
  }
}

}  // namespace
}  // namespace mocaplink::sources

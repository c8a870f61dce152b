// The dashboard never locks the operator out (issue 15): with 100 idle connections (a half-sent
// request each: stuck tabs, a port scanner), all 8 event streams open and a client sending one
// byte per second, GET /api/status and a PATCH are still answered. No timing is asserted: the
// requests only have to be answered before a generous client deadline (how fast they are is
// measured by bench/web_crowd, docs/performance.md).
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "api_fixture.hpp"
#include "raw_client.hpp"

namespace mocaplink::web::testing {
namespace {

TEST_F(ApiTest, IdleSlowAndStreamingClientsDoNotLockTheOperatorOut) {
  const std::uint16_t port = server_->port();
  // 100 idle connections from four addresses (25 each, within the cap of 32 per address; the
  // cap itself is api_limits_test's): a crowd of tabs and scanners on the lab network.
  std::vector<int> idle;
  const char* const crowd[] = {"127.0.0.2", "127.0.0.3", "127.0.0.4", "127.0.0.5"};
  for (int i = 0; i < 100; ++i) {
    const int fd =
        connect_and_send(port, "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n", crowd[i % 4]);
    ASSERT_GE(fd, 0) << "idle connection " << i;
    idle.push_back(fd);
  }

  // 8 event streams (the allowed number), each confirmed open by its first event.
  std::mutex mutex;
  std::condition_variable cv;
  int streaming = 0;
  std::atomic<bool> done{false};
  std::vector<std::thread> streams;
  for (int i = 0; i < 8; ++i) {
    streams.emplace_back([&, port] {
      httplib::Client client("127.0.0.1", port);
      client.set_read_timeout(60, 0);
      bool counted = false;
      client.Get("/api/events", [&](const char*, std::size_t) {
        if (!counted) {
          counted = true;
          std::lock_guard lock(mutex);
          ++streaming;
          cv.notify_all();
        }
        return !done.load();
      });
    });
  }
  {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return streaming == 8; });
  }

  // One byte per second of a request that is never finished in time.
  std::thread slow([&, port] {
    const std::string request = "PATCH /api/vehicles/quad1 HTTP/1.1\r\nHost: 127.0.0.1\r\n";
    const int fd = connect_and_send(port, "");
    for (std::size_t i = 0; fd >= 0 && i < request.size() && !done.load(); ++i) {
      if (::send(fd, &request[i], 1, MSG_NOSIGNAL) < 0) break;
      std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    if (fd >= 0) ::close(fd);
  });

  // The operator: a fresh client with a generous deadline (a locked-out dashboard waits forever).
  httplib::Client operator_client("127.0.0.1", port);
  operator_client.set_connection_timeout(30, 0);
  operator_client.set_read_timeout(30, 0);
  const auto status = operator_client.Get("/api/status");
  ASSERT_TRUE(status) << httplib::to_string(status.error());
  EXPECT_EQ(status->status, 200);
  const auto changed =
      operator_client.Patch("/api/vehicles/quad1", R"({"rate_hz": 12.5})", "application/json");
  ASSERT_TRUE(changed) << httplib::to_string(changed.error());
  EXPECT_EQ(changed->status, 200);

  done = true;
  for (const int fd : idle) ::close(fd);
  server_->stop();  // ends the event streams
  for (auto& t : streams) t.join();
  slow.join();
}

}  // namespace
}  // namespace mocaplink::web::testing

// The dashboard's connection limits over real sockets (issue 15): one client address cannot hold
// more than max_connections_per_client connections (the next one is closed unread and counted,
// while other addresses are still served), and a request that does not arrive within the request
// deadline is answered 408 and closed, even when its client never stays silent for long. No
// timing is asserted: the tests wait for readiness (the server's own counters) and for the server
// to act; the deadlines in the configuration only make the runs short.
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "api_fixture.hpp"
#include "raw_client.hpp"

namespace mocaplink::web::testing {
namespace {

/// GET /api/status from `from` (a 127.x.y.z address); the "http" object of the answer.
nlohmann::json http_counters(std::uint16_t port, const char* from) {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(30, 0);
  client.set_socket_options([from](socket_t sock) {
    sockaddr_in local{};
    local.sin_family = AF_INET;
    ::inet_pton(AF_INET, from, &local.sin_addr);
    ::bind(sock, reinterpret_cast<sockaddr*>(&local), sizeof local);
  });
  const auto status = client.Get("/api/status");
  if (!status || status->status != 200) return nullptr;
  return nlohmann::json::parse(status->body).at("http");
}

/// The "http" object once `ready` holds for it (the status is cached for half an event period,
/// so a count shows up a moment later); null when `from` is not served.
template <typename Ready>
nlohmann::json wait_for_counters(std::uint16_t port, const char* from, Ready ready) {
  while (true) {
    nlohmann::json counters = http_counters(port, from);
    if (counters.is_null() || ready(counters)) return counters;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

int count(const nlohmann::json& counters, const char* key) {
  return counters.at(key).get<int>();
}

class ApiLimitsTest : public ApiTest {
 protected:
  void SetUp() override {}  // each test starts the server with its own limits
};

TEST_F(ApiLimitsTest, AClientAddressOverItsCapIsRefusedWhileOthersAreServed) {
  // Long timeouts: the held connections must stay open until the test has looked.
  start(DashboardServerConfig{.max_connections_per_client = 32,
                              .request_timeout = std::chrono::minutes(5),
                              .idle_timeout = std::chrono::minutes(5)});
  const std::uint16_t port = server_->port();
  std::vector<int> held;
  for (int i = 0; i < 32; ++i) {
    const int fd = connect_and_send(port, "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n");
    ASSERT_GE(fd, 0) << "connection " << i;
    held.push_back(fd);
  }
  // Ready when the server serves all 32 (plus the connection asking, from another address).
  nlohmann::json counters = wait_for_counters(
      port, "127.0.0.2", [](const auto& c) { return count(c, "connections_open") >= 33; });
  ASSERT_FALSE(counters.is_null()) << "127.0.0.2 was not served";
  EXPECT_EQ(counters.at("connections_refused"), 0);

  // The 33rd from 127.0.0.1 is closed without an answer.
  const int refused = connect_and_send(port, "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  ASSERT_GE(refused, 0);
  EXPECT_EQ(read_until_closed(refused), "");
  ::close(refused);

  // Another address is still served, and sees the refusal counted.
  counters = wait_for_counters(port, "127.0.0.3",
                               [](const auto& c) { return count(c, "connections_refused") > 0; });
  ASSERT_FALSE(counters.is_null()) << "127.0.0.3 was not served";
  EXPECT_EQ(counters.at("connections_refused"), 1);

  // A slot given back can be taken again by the same address.
  ::close(held.back());
  held.pop_back();
  counters = wait_for_counters(port, "127.0.0.2",
                               [](const auto& c) { return count(c, "connections_open") <= 32; });
  ASSERT_FALSE(counters.is_null());
  EXPECT_FALSE(http_counters(port, "127.0.0.1").is_null());

  for (const int fd : held) ::close(fd);
}

TEST_F(ApiLimitsTest, ARequestThatDoesNotArriveInTimeIsAnswered408AndClosed) {
  // The client sends a byte every 100 ms, far inside the 2 s silence limit, of a request that
  // would take hours to finish: only the whole-request deadline can end it.
  start(DashboardServerConfig{.request_timeout = std::chrono::milliseconds(500)});
  const std::uint16_t port = server_->port();
  const int fd = connect_and_send(port, "GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ");
  ASSERT_GE(fd, 0);
  std::atomic<bool> answered{false};
  std::thread slow([fd, &answered] {
    for (int i = 0; i < 100000 && !answered.load(); ++i) {
      if (::send(fd, "a", 1, MSG_NOSIGNAL) < 0) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  const std::string answer = read_until_closed(fd);
  answered = true;
  slow.join();
  ::close(fd);
  EXPECT_EQ(answer.rfind("HTTP/1.1 408 Request Timeout\r\n", 0), 0U) << answer;

  const nlohmann::json counters = wait_for_counters(
      port, "127.0.0.1", [](const auto& c) { return count(c, "requests_timed_out") > 0; });
  ASSERT_FALSE(counters.is_null());
  EXPECT_EQ(counters.at("requests_timed_out"), 1);
  EXPECT_EQ(counters.at("connections_refused"), 0);
}

TEST_F(ApiLimitsTest, ABodyThatStopsHalfwayIsAnswered408) {
  start(DashboardServerConfig{.request_timeout = std::chrono::milliseconds(500),
                              .idle_timeout = std::chrono::milliseconds(200)});
  const int fd = connect_and_send(server_->port(),
                                  "PATCH /api/vehicles/quad1 HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                  "Content-Type: application/json\r\nContent-Length: 20\r\n\r\n"
                                  "{\"rate_hz\":");
  ASSERT_GE(fd, 0);
  const std::string answer = read_until_closed(fd);
  ::close(fd);
  EXPECT_EQ(answer.rfind("HTTP/1.1 408 Request Timeout\r\n", 0), 0U) << answer;
  EXPECT_EQ(backend_.applied().size(), 0U);
}

TEST_F(ApiLimitsTest, LimitsOfZeroAreRefusedAtStart) {
  for (const DashboardServerConfig& config :
       {DashboardServerConfig{.port = 0, .max_connections_per_client = 0},
        DashboardServerConfig{.port = 0, .request_timeout = std::chrono::milliseconds(0)},
        DashboardServerConfig{.port = 0, .idle_timeout = std::chrono::milliseconds(0)}}) {
    DashboardServer server(backend_, config);
    EXPECT_EQ(server.start(), "the dashboard connection limits must be positive");
  }
}

}  // namespace
}  // namespace mocaplink::web::testing

// DNS rebinding (issue 26): a page on any site can point its own name at 127.0.0.1 after it has
// loaded, and the browser then sends its requests to the dashboard with that name as Host (and as
// Origin, so the Origin check passes). Without a token, only the Host tells such a request apart.
// The five requests such a page would make, with a foreign Host, are refused and change nothing;
// the same requests naming the server work.
#include <string>
#include <vector>

#include "api_fixture.hpp"
#ifndef _WIN32
#include "raw_client.hpp"
#endif

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

constexpr const char* kHostTestToken = "s3cret-token-0123456789";
constexpr const char* kIntruderSpec =
    R"({"name":"intruder","body":"Body2","link":"udp://203.0.113.7:14550"})";

struct Outcome {
  int status = 0;
  json body;
};

class HostTest : public ApiTest {
 protected:
  [[nodiscard]] std::string with_port(const std::string& host) const {
    return host + ":" + std::to_string(server_->port());
  }

  /// What the five requests of a rebinding page get when they name `host` (with the same-site
  /// Origin a browser sends on the writes), in the order of the issue: GET /api/status, GET
  /// /api/events (only its status line: a stream does not end), PATCH, POST, DELETE.
  std::vector<Outcome> five_requests(const std::string& host, const httplib::Headers& extra = {}) {
    httplib::Headers read = extra;
    read.emplace("Host", host);
    httplib::Headers write = read;
    write.emplace("Origin", "http://" + host);
    std::vector<Outcome> out;
    const auto add = [&out](const httplib::Result& res) {
      ASSERT_TRUE(res);
      out.push_back({res->status, json::parse(res->body, nullptr, false)});
    };
    add(get("/api/status", read));
    // The event stream does not end: take its status and hang up before the body.
    int events_status = 0;
    (void)client_->Get(
        "/api/events", read,
        [&events_status](const httplib::Response& res) {
          events_status = res.status;
          return false;
        },
        [](const char*, std::size_t) { return false; });
    out.push_back({events_status, json()});
    add(patch("/api/vehicles/quad1", R"({"paused": true})", write));
    add(post("/api/vehicles", kIntruderSpec, write));
    add(del("/api/vehicles/rover", write));
    return out;
  }

  /// The five requests naming `host` are all obeyed; then the lab is put back for the next name
  /// (the intruder gone, the rover there again).
  void expect_all_obeyed(const std::string& host) {
    const auto outcomes = five_requests(host);
    ASSERT_EQ(outcomes.size(), 5U);
    const std::vector<int> obeyed = {200, 200, 200, 201, 204};
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      EXPECT_EQ(outcomes[i].status, obeyed[i]) << host << ", request " << i + 1;
    }
    (void)backend_.apply(RemoveVehicle{"intruder"});
    auto rover =
        parse_vehicle_spec(R"({"name":"rover","body":"Body2","link":"udp://127.0.0.1:14541"})");
    ASSERT_TRUE(rover.ok());
    (void)backend_.apply(rover.value());
  }

  /// The vehicles as the operator's own page sees them (Host 127.0.0.1:PORT).
  json vehicles() {
    auto res = get("/api/vehicles");
    EXPECT_TRUE(res && res->status == 200);
    return res ? json::parse(res->body) : json();
  }
};

TEST_F(HostTest, AForeignHostIsRefusedAndChangesNothing) {
  const json before = vehicles();
  ASSERT_EQ(before.size(), 2U);
  for (const std::string& host :
       {with_port("evil.example"), std::string("evil.example"), with_port("lab-pc"),
        with_port("127.0.0.1.evil.example"), with_port("localhost.evil.example"),
        with_port("192.168.1.10"), with_port("0.0.0.0"), with_port("[::2]")}) {
    const auto outcomes = five_requests(host);
    ASSERT_EQ(outcomes.size(), 5U);
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      EXPECT_EQ(outcomes[i].status, 403) << host << ", request " << i + 1;
      if (i == 1) continue;  // the stream's body is not read
      const json& body = outcomes[i].body;
      ASSERT_TRUE(body.is_object()) << host << ", request " << i + 1;
      EXPECT_EQ(body.size(), 2U) << body.dump();  // error and field only: no status leaks
      const std::string error = body.value("error", "");
      EXPECT_NE(error.find("Host \"" + host + "\""), std::string::npos) << error;
      EXPECT_NE(error.find("allowed_hosts"), std::string::npos) << error;
      EXPECT_NE(error.find("--http-allow-host"), std::string::npos) << error;
    }
  }
  EXPECT_TRUE(backend_.applied().empty());
  EXPECT_EQ(vehicles(), before);
}

TEST_F(HostTest, EveryPathIsGuardedPageFilesIncluded) {
  const httplib::Headers foreign = {{"Host", with_port("evil.example")}};
  for (const char* path : {"/", "/app.js", "/style.css", "/no-such-file", "/api", "/api/nothing",
                           "/api/vehicles", "/api/vehicles/quad1"}) {
    auto res = get(path, foreign);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 403) << path;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/json") << path;
    EXPECT_EQ(res->body.find("<html"), std::string::npos) << path;
  }
  auto page = get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
}

TEST_F(HostTest, LoopbackNamesWorkWithOrWithoutTheListeningPort) {
  for (const std::string& host :
       {with_port("127.0.0.1"), std::string("127.0.0.1"), with_port("127.1.2.3"),
        with_port("localhost"), std::string("localhost"), with_port("LocalHost"),
        with_port("[::1]"), std::string("[::1]")}) {
    expect_all_obeyed(host);
  }
  EXPECT_EQ(backend_.applied().size(), 8U * 3U + 8U * 2U);
}

TEST_F(HostTest, ALoopbackNameWithAnotherPortIsRefused) {
  const std::uint16_t other = server_->port() == 65535 ? 1 : server_->port() + 1;
  for (const std::string& host : {"127.0.0.1:" + std::to_string(other), std::string("localhost:80"),
                                  "[::1]:" + std::to_string(other)}) {
    auto res = get("/api/status", {{"Host", host}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 403) << host;
  }
}

TEST_F(HostTest, MalformedHostsAreRefused) {
  // (Spaces around a value are not part of it, RFC 9110 §5.5: "127.0.0.1 " arrives as 127.0.0.1.)
  for (const std::string& host :
       {std::string(""), std::string(":") + std::to_string(server_->port()), std::string("::1"),
        std::string("127.0.0.1:"), std::string("127.0.0.1:0"), std::string("127.0.0.1:99999"),
        std::string("127.0.0.1:80a"), std::string("[::1"), std::string("local host"),
        std::string("localhost/"), std::string("localhost:8080:8080"),
        std::string("user@localhost"), std::string("localhost\x7f"), std::string("[127.0.0.1]"),
        std::string(300, 'a')}) {
    auto res = get("/api/status", {{"Host", host}});
    ASSERT_TRUE(res) << host;
    EXPECT_EQ(res->status, 403) << host;
    // The answer is JSON whatever the Host held, and shows at most 100 of its characters.
    const json body = json::parse(res->body, nullptr, false);
    ASSERT_TRUE(body.is_object()) << res->body;
    EXPECT_LT(body.value("error", "").size(), 500U);
  }
}

TEST_F(HostTest, RefusalsAreCountedInTheStatus) {
  for (int i = 0; i < 3; ++i) {
    auto res = get("/api/status", {{"Host", "evil.example"}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 403);
  }
  auto status = get("/api/status");
  ASSERT_TRUE(status);
  EXPECT_EQ(body_json(status)["http"]["requests_host_refused"], 3);
}

#ifndef _WIN32
// httplib's client always sends one Host; these need a raw connection.
TEST_F(HostTest, AMissingOrRepeatedHostIsRefused) {
  const std::string local = with_port("127.0.0.1");
  for (const std::string& head :
       {std::string("GET /api/status HTTP/1.1\r\n"), std::string("GET /api/status HTTP/1.0\r\n"),
        "GET /api/status HTTP/1.1\r\nHost: " + local + "\r\nHost: evil.example\r\n",
        "GET /api/status HTTP/1.1\r\nHost: evil.example\r\nHost: " + local + "\r\n",
        "GET /api/status HTTP/1.1\r\nHost: " + local + "\r\nHost: " + local + "\r\n",
        "GET http://" + local + "/api/status HTTP/1.1\r\nHost: evil.example\r\n"}) {
    const int fd = connect_and_send(server_->port(), head + "Connection: close\r\n\r\n");
    ASSERT_GE(fd, 0);
    const std::string answer = read_until_closed(fd);
    ::close(fd);
    EXPECT_EQ(answer.rfind("HTTP/1.1 403 ", 0), 0U) << head << "\n" << answer;
    EXPECT_EQ(answer.find("\"vehicles\""), std::string::npos) << answer;
  }
  const int fd = connect_and_send(server_->port(), "GET /api/status HTTP/1.1\r\nHost: " + local +
                                                       "\r\nConnection: close\r\n\r\n");
  ASSERT_GE(fd, 0);
  EXPECT_EQ(read_until_closed(fd).rfind("HTTP/1.1 200 ", 0), 0U);
  ::close(fd);
}
#endif

class AllowedHostTest : public HostTest {
 protected:
  void SetUp() override {
    DashboardServerConfig config;
    config.allowed_hosts = {{"lab-pc", 0}, {"lab-pc.local", 0}, {"tunnel", 9000}};
    start(config);
  }
};

TEST_F(AllowedHostTest, AnAllowedNameWorksAndOthersStillDoNot) {
  for (const std::string& host : {with_port("lab-pc"), std::string("lab-pc"),
                                  with_port("LAB-PC.local"), std::string("tunnel:9000")}) {
    expect_all_obeyed(host);
  }
  for (const std::string& host :
       {with_port("evil.example"), std::string("lab-pc:9000"), with_port("tunnel"),
        std::string("tunnel"), with_port("pc"), with_port("lab-pc.local.evil.example")}) {
    auto res = get("/api/status", {{"Host", host}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 403) << host;
  }
}

class TokenHostTest : public HostTest {
 protected:
  void SetUp() override {
    DashboardServerConfig config;
    config.token = kHostTestToken;
    start(config);
  }
  const httplib::Headers good_ = {{"Authorization", std::string("Bearer ") + kHostTestToken}};
};

// With a token the token is the protection: a rebinding page cannot read it (it is kept by the
// operator's tab under the dashboard's own origin), and a dashboard on 0.0.0.0 is reached by
// addresses it cannot know.
TEST_F(TokenHostTest, WithATokenAnyHostIsAnsweredButTheTokenIsStillNeeded) {
  const auto without = five_requests(with_port("evil.example"));
  for (std::size_t i = 0; i < without.size(); ++i) {
    EXPECT_EQ(without[i].status, 401) << "request " << i + 1;
  }
  EXPECT_TRUE(backend_.applied().empty());
  const auto with = five_requests(with_port("192.168.1.10"), good_);
  EXPECT_EQ(with[0].status, 200);
  EXPECT_EQ(with[2].status, 200);
  EXPECT_EQ(with[3].status, 201);
  EXPECT_EQ(with[4].status, 204);
}

TEST_F(TokenHostTest, WithATokenAndAllowedHostsBothAreChecked) {
  server_->stop();
  DashboardServerConfig config;
  config.token = kHostTestToken;
  config.allowed_hosts = {{"lab-pc", 0}};
  start(config);
  auto foreign = get("/api/status", {{"Host", "evil.example"}, *good_.begin()});
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  auto named = get("/api/status", {{"Host", "lab-pc"}, *good_.begin()});
  ASSERT_TRUE(named);
  EXPECT_EQ(named->status, 200);
  auto local = get("/api/status", {{"Host", "localhost"}, *good_.begin()});
  ASSERT_TRUE(local);
  EXPECT_EQ(local->status, 200);
}

}  // namespace
}  // namespace mocaplink::web::testing

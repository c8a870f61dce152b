// Who may use the API: tokens, loopback-only without a token, cross-origin refusal, bind errors.
#include "api_fixture.hpp"

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

constexpr const char* kToken = "s3cret-token-0123456789";

class TokenTest : public ApiTest {
 protected:
  void SetUp() override {
    DashboardServerConfig config;
    config.token = kToken;
    start(config);
  }
  const httplib::Headers good_ = {{"Authorization", std::string("Bearer ") + kToken}};
};

TEST_F(TokenTest, EveryApiRequestNeedsTheBearerToken) {
  for (const auto& headers :
       std::vector<httplib::Headers>{{},
                                     {{"Authorization", "Bearer wrong"}},
                                     {{"Authorization", std::string("Bearer ") + kToken + "x"}},
                                     {{"Authorization", std::string("Basic ") + kToken}},
                                     {{"Authorization", kToken}}}) {
    for (const char* path : {"/api/status", "/api/vehicles", "/api/vehicles/quad1"}) {
      auto res = get(path, headers);
      ASSERT_TRUE(res);
      EXPECT_EQ(res->status, 401) << path;
      EXPECT_EQ(res->get_header_value("WWW-Authenticate"), "Bearer realm=\"mocaplink\"");
      EXPECT_EQ(body_json(res)["field"], "");
    }
  }
  EXPECT_EQ(backend_.status_calls(), 0);  // nothing was read for an unauthenticated client
  auto ok = get("/api/status", good_);
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  auto lower_case_scheme = get("/api/status", {{"Authorization", std::string("bearer ") + kToken}});
  ASSERT_TRUE(lower_case_scheme);
  EXPECT_EQ(lower_case_scheme->status, 200);
}

TEST_F(TokenTest, MutationsNeedTheTokenToo) {
  auto refused_patch = patch("/api/vehicles/quad1", R"({"paused": true})");
  ASSERT_TRUE(refused_patch);
  EXPECT_EQ(refused_patch->status, 401);
  auto refused_post = post("/api/vehicles", R"({"name":"a","body":"b","link":"udp://h:1"})");
  ASSERT_TRUE(refused_post);
  EXPECT_EQ(refused_post->status, 401);
  auto refused_delete = del("/api/vehicles/quad1");
  ASSERT_TRUE(refused_delete);
  EXPECT_EQ(refused_delete->status, 401);
  EXPECT_TRUE(backend_.applied().empty());

  auto accepted = patch("/api/vehicles/quad1", R"({"paused": true})", good_);
  ASSERT_TRUE(accepted);
  EXPECT_EQ(accepted->status, 200);
  EXPECT_EQ(backend_.applied().size(), 1U);
}

TEST_F(TokenTest, ThePageItselfIsPublic) {
  // A browser cannot attach a header to a page load; the page holds no data and asks for the
  // token before calling the API.
  auto res = get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
}

TEST_F(ApiTest, NonLoopbackWithoutATokenRefusesToStart) {
  FakeBackend backend;
  for (const char* host : {"0.0.0.0", "", "192.168.1.10", "::"}) {
    DashboardServer server(backend, DashboardServerConfig{.host = host, .port = 0});
    const auto error = server.start();
    ASSERT_TRUE(error.has_value()) << host;
    EXPECT_NE(error->find("refusing to listen"), std::string::npos) << *error;
    EXPECT_NE(error->find("token"), std::string::npos) << *error;
    EXPECT_EQ(server.port(), 0);
  }
}

TEST_F(ApiTest, NonLoopbackWithATokenStarts) {
  FakeBackend backend;
  DashboardServer server(backend,
                         DashboardServerConfig{.host = "0.0.0.0", .port = 0, .token = kToken});
  const auto error = server.start();
  ASSERT_FALSE(error.has_value()) << *error;
  httplib::Client client("127.0.0.1", server.port());
  auto res = client.Get("/api/status");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 401);
}

TEST_F(ApiTest, APortInUseIsAClearError) {
  FakeBackend backend;
  DashboardServer second(backend,
                         DashboardServerConfig{.host = "127.0.0.1", .port = server_->port()});
  const auto error = second.start();
  ASSERT_TRUE(error.has_value());
#ifdef _WIN32
  // Windows's own text for the error (its wording varies by language), then the number.
  const std::string prefix = "cannot listen on 127.0.0.1:" + std::to_string(server_->port()) + ": ";
  EXPECT_EQ(error->rfind(prefix, 0), 0u) << *error;
  EXPECT_TRUE(error->ends_with(" (WSA error 10048)")) << *error;  // WSAEADDRINUSE
  EXPECT_GT(error->size(), prefix.size() + std::string(" (WSA error 10048)").size()) << *error;
#else
  EXPECT_EQ(*error, "cannot listen on 127.0.0.1:" + std::to_string(server_->port()) +
                        ": Address already in use");
#endif
  // The first server is unaffected.
  EXPECT_EQ(get("/api/status")->status, 200);
}

TEST_F(ApiTest, AnUnresolvableHostIsAClearError) {
  FakeBackend backend;
  DashboardServer server(
      backend, DashboardServerConfig{.host = "no-such-host.invalid", .port = 0, .token = kToken});
  const auto error = server.start();
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->rfind("cannot listen on no-such-host.invalid:0: ", 0), 0U) << *error;
}

TEST_F(ApiTest, CrossOriginMutationsAreRefused) {
  auto evil =
      patch("/api/vehicles/quad1", R"({"paused": true})", {{"Origin", "http://evil.example"}});
  ASSERT_TRUE(evil);
  EXPECT_EQ(evil->status, 403);
  auto evil_delete = del("/api/vehicles/quad1", {{"Origin", "null"}});
  ASSERT_TRUE(evil_delete);
  EXPECT_EQ(evil_delete->status, 403);
  EXPECT_TRUE(backend_.applied().empty());

  const std::string self = "http://127.0.0.1:" + std::to_string(server_->port());
  auto same = patch("/api/vehicles/quad1", R"({"paused": true})", {{"Origin", self}});
  ASSERT_TRUE(same);
  EXPECT_EQ(same->status, 200);
}

TEST_F(ApiTest, StartingTwiceIsAnError) {
  const auto error = server_->start();
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("already started"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::web::testing

// POST / PATCH / DELETE /api/vehicles over real HTTP: every mutation, every validation error, and
// that a refused request changes nothing.
#include <chrono>
#include <thread>
#include <variant>

#include "api_fixture.hpp"

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

/// The value of `key` among the keys the server passed on; std::nullopt when it did not.
std::optional<config::VehicleKey::Value> key_value(const std::vector<config::VehicleKey>& keys,
                                                   const std::string& key) {
  for (const auto& k : keys) {
    if (k.key == key) return k.value;
  }
  return std::nullopt;
}

using Value = config::VehicleKey::Value;

const json kNewVehicle = {{"name", "hexa"},
                          {"body", "Body2"},
                          {"link", "udp://10.0.0.7:14540"},
                          {"system_id", 7},
                          {"profile", "custom"},
                          {"messages", {"vision_position_estimate", "vision_speed_estimate"}},
                          {"rate_hz", 30},
                          {"paused", true}};

TEST_F(ApiTest, PostAddsAVehicleAndReturnsIt) {
  auto res = post("/api/vehicles", kNewVehicle.dump());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  EXPECT_EQ(res->get_header_value("Location"), "/api/vehicles/hexa");
  const json created = body_json(res);
  EXPECT_EQ(created["name"], "hexa");
  EXPECT_EQ(created["messages"], kNewVehicle["messages"]);
  EXPECT_EQ(created["paused"], true);

  const auto applied = backend_.applied();
  ASSERT_EQ(applied.size(), 1U);
  const auto* add = std::get_if<AddVehicle>(&applied[0]);
  ASSERT_NE(add, nullptr);
  // The [[vehicle]] keys go on typed as JSON gave them; `paused` is the API's own.
  EXPECT_EQ(add->name, "hexa");
  EXPECT_EQ(add->keys.size(), 7U);
  EXPECT_EQ(key_value(add->keys, "name"), Value(std::string("hexa")));
  EXPECT_EQ(key_value(add->keys, "body"), Value(std::string("Body2")));
  EXPECT_EQ(key_value(add->keys, "link"), Value(std::string("udp://10.0.0.7:14540")));
  EXPECT_EQ(key_value(add->keys, "system_id"), Value(std::int64_t{7}));
  EXPECT_EQ(key_value(add->keys, "profile"), Value(std::string("custom")));
  EXPECT_EQ(key_value(add->keys, "messages"),
            Value(std::vector<std::string>{"vision_position_estimate", "vision_speed_estimate"}));
  EXPECT_EQ(key_value(add->keys, "rate_hz"), Value(std::int64_t{30}));
  EXPECT_FALSE(key_value(add->keys, "paused"));
  EXPECT_FALSE(key_value(add->keys, "signing_key"));
  EXPECT_TRUE(add->paused);

  const json vehicles = body_json(get("/api/vehicles"));
  ASSERT_EQ(vehicles.size(), 3U);  // the change shows at once (no stale cached status)
  EXPECT_EQ(vehicles[2]["name"], "hexa");
}

TEST_F(ApiTest, PostThatSucceededIsNeverAnsweredAs404) {
  // The daemon applied the add but its status still shows the previous picture (slow loop).
  backend_.set_status_frozen(true);
  auto res = post("/api/vehicles", kNewVehicle.dump());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  EXPECT_EQ(res->get_header_value("Location"), "/api/vehicles/hexa");
  EXPECT_EQ(body_json(res), (json{{"name", "hexa"}}));
  ASSERT_EQ(backend_.applied().size(), 1U);
  backend_.set_status_frozen(false);
  // Once the shared snapshot (kept for half an event period) is renewed, it is there.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(get("/api/vehicles/hexa")->status, 200);
}

TEST_F(ApiTest, PostDefaultsFollowTheConfigFile) {
  auto res = post("/api/vehicles", R"({"name":"q2","body":"Body3","link":"udp://h:1"})");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body;
  const auto applied = backend_.applied();
  ASSERT_EQ(applied.size(), 1U);
  // The given keys go on, with the API's defaults for system_id and profile (a file must give
  // them); the other defaults are the configuration's.
  const auto& add = std::get<AddVehicle>(applied[0]);
  EXPECT_EQ(add.keys.size(), 5U);
  EXPECT_EQ(key_value(add.keys, "system_id"), Value(std::int64_t{1}));
  EXPECT_EQ(key_value(add.keys, "profile"), Value(std::string("px4")));
  EXPECT_FALSE(key_value(add.keys, "rate_hz"));
  EXPECT_FALSE(add.paused);
  const json created = body_json(res);
  EXPECT_EQ(created["system_id"], 1);
  EXPECT_EQ(created["profile"], "px4");
  EXPECT_EQ(created["messages"], json::array({"odometry"}));
  EXPECT_DOUBLE_EQ(created["rate_hz"].get<double>(), 50.0);
  EXPECT_EQ(created["paused"], false);
}

struct BadPost {
  std::string body;
  int status;
  std::string field;
  std::string error_part;  // a substring of the error sentence
};

TEST_F(ApiTest, EveryInvalidPostIsRefusedNamingTheFieldAndChangesNothing) {
  auto with = [](const char* key, json value) {
    json v = {{"name", "n1"}, {"body", "Body1"}, {"link", "udp://10.0.0.2:14540"}};
    v[key] = std::move(value);
    return v.dump();
  };
  auto without = [](const char* key) {
    json v = {{"name", "n1"}, {"body", "Body1"}, {"link", "udp://10.0.0.2:14540"}};
    v.erase(key);
    return v.dump();
  };
  const std::vector<BadPost> cases = {
      {"{", 400, "", "not valid JSON"},
      {"[1,2]", 400, "", "JSON object"},
      {without("name"), 422, "name", "required"},
      {without("body"), 422, "body", "required"},
      {without("link"), 422, "link", "required"},
      {with("name", "quad 1"), 422, "name", "1 to 64 letters, digits"},
      {with("name", std::string(65, 'a')), 422, "name", "1 to 64 letters, digits"},
      {with("name", 5), 422, "name", "expected a string, got an integer"},
      {with("body", ""), 422, "body", "1 to 256 characters"},
      {with("body", "a\nb"), 422, "body", "control"},
      {with("link", "http://10.0.0.2"), 422, "link", "udp://"},
      {with("system_id", 0), 422, "system_id", "from 1 to 255, got 0"},
      {with("system_id", 256), 422, "system_id", "from 1 to 255, got 256"},
      {with("system_id", 1.5), 422, "system_id", "expected an integer, got a number"},
      {with("profile", "px5"), 422, "profile", "px4"},
      {with("rate_hz", 0), 422, "rate_hz", "must be above 0 and at most 500, got 0"},
      {with("rate_hz", 500.5), 422, "rate_hz", "at most 500, got 500.5"},
      {with("rate_hz", "50"), 422, "rate_hz", "expected a number, got a string"},
      {with("messages", json::array({"odometry"})), 422, "messages",
       "only allowed with profile = \"custom\""},
      {with("messages", "odometry"), 422, "messages", "expected an array of strings"},
      {with("messages", json::array({1})), 422, "messages", "an array of strings, got [1]"},
      {with("body", nullptr), 422, "body", "got null"},
      {with("signing_key", "abc"), 422, "signing_key", "64 hexadecimal characters"},
      {with("signing_key", std::string(64, 'g')), 422, "signing_key", "including non-hex"},
      {with("paused", "yes"), 422, "paused", "true or false"},
      {with("rate", 50), 422, "rate", "did you mean \"rate_hz\""},
      {with("colour", "red"), 422, "colour", "expected one of"},
      // The backend's own refusals pass through unchanged.
      {with("name", "quad1"), 409, "name", "exists"},
      {with("link", "udp://10.0.0.2"), 422, "link", "missing port"},
  };
  auto custom = [](json messages) {
    json v = {{"name", "n1"}, {"body", "B"}, {"link", "udp://h:1"}, {"profile", "custom"}};
    if (!messages.is_null()) v["messages"] = std::move(messages);
    return v.dump();
  };
  std::vector<BadPost> custom_cases = {
      {custom(nullptr), 422, "messages", "needs a messages list"},
      {custom(json::array()), 422, "messages", "at least one"},
      {custom({"odometry", "teleport"}), 422, "messages", "unknown message \"teleport\""},
      {custom({"odometry", "odometry"}), 422, "messages", "\"odometry\" is listed twice"},
  };
  std::vector<BadPost> all = cases;
  all.insert(all.end(), custom_cases.begin(), custom_cases.end());
  for (const BadPost& c : all) {
    SCOPED_TRACE(c.body);
    auto res = post("/api/vehicles", c.body);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, c.status);
    const json error = body_json(res);
    EXPECT_EQ(error["field"], c.field);
    EXPECT_NE(error["error"].get<std::string>().find(c.error_part), std::string::npos)
        << error["error"];
  }
  EXPECT_TRUE(backend_.applied().empty());
  EXPECT_EQ(body_json(get("/api/vehicles")).size(), 2U);
}

TEST_F(ApiTest, PatchChangesRateMessagesAndPauseAtOnce) {
  auto rate = patch("/api/vehicles/quad1", R"({"rate_hz": 12.5})");
  ASSERT_TRUE(rate);
  ASSERT_EQ(rate->status, 200) << rate->body;
  EXPECT_DOUBLE_EQ(body_json(rate)["rate_hz"].get<double>(), 12.5);

  auto messages = patch("/api/vehicles/quad1", R"({"messages": []})");
  ASSERT_TRUE(messages);
  ASSERT_EQ(messages->status, 200);
  EXPECT_EQ(body_json(messages)["messages"], json::array());

  auto both = patch("/api/vehicles/rover", R"({"paused": true, "messages": ["hil_gps"]})");
  ASSERT_TRUE(both);
  ASSERT_EQ(both->status, 200);
  EXPECT_EQ(body_json(both)["paused"], true);
  EXPECT_EQ(body_json(both)["messages"], json::array({"hil_gps"}));

  const auto applied = backend_.applied();
  ASSERT_EQ(applied.size(), 3U);
  const auto& first = std::get<UpdateVehicle>(applied[0]);
  EXPECT_EQ(first.name, "quad1");
  EXPECT_EQ(key_value(first.keys, "rate_hz"), Value(12.5));
  EXPECT_FALSE(key_value(first.keys, "messages"));
  EXPECT_FALSE(first.paused.has_value());
  const auto& third = std::get<UpdateVehicle>(applied[2]);
  EXPECT_EQ(third.paused, true);
  EXPECT_FALSE(key_value(third.keys, "rate_hz"));
  EXPECT_EQ(key_value(third.keys, "messages"), Value(std::vector<std::string>{"hil_gps"}));
}

TEST_F(ApiTest, EveryInvalidPatchIsRefusedAndNothingIsHalfApplied) {
  const std::vector<BadPost> cases = {
      {R"({"paused": true, "rate_hz": -1})", 422, "rate_hz", "above 0 and at most 500, got -1"},
      {R"({"rate_hz": 20, "messages": ["odometry", "odometry"]})", 422, "messages", "twice"},
      {R"({"messages": "odometry"})", 422, "messages", "expected an array of strings"},
      {R"({"paused": true, "messages": ["odometry", "nope"]})", 422, "messages",
       "unknown message \"nope\""},
      {R"({"rate_hz": 20, "paused": 1})", 422, "paused", "true or false"},
      {R"({"rate_hz": 20, "profile": "ardupilot"})", 422, "profile", "unknown key"},
      {R"({})", 422, "", "nothing to change"},
      {R"(nonsense)", 400, "", "not valid JSON"},
  };
  for (const BadPost& c : cases) {
    SCOPED_TRACE(c.body);
    auto res = patch("/api/vehicles/quad1", c.body);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, c.status);
    EXPECT_EQ(body_json(res)["field"], c.field);
    EXPECT_NE(body_json(res)["error"].get<std::string>().find(c.error_part), std::string::npos);
  }
  EXPECT_TRUE(backend_.applied().empty());
  const json quad = body_json(get("/api/vehicles/quad1"));
  EXPECT_EQ(quad["paused"], false);
  EXPECT_DOUBLE_EQ(quad["rate_hz"].get<double>(), 50.0);
}

TEST_F(ApiTest, PatchOfAnUnknownVehicleIs404) {
  auto res = patch("/api/vehicles/ghost", R"({"rate_hz": 10})");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  auto bad_name = patch("/api/vehicles/bad%20name", R"({"rate_hz": 10})");
  ASSERT_TRUE(bad_name);
  EXPECT_EQ(bad_name->status, 404);
}

TEST_F(ApiTest, PatchNeedsAJsonContentType) {
  auto res = client_->Patch("/api/vehicles/quad1", R"({"rate_hz": 10})", "text/plain");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 415);
  EXPECT_TRUE(backend_.applied().empty());
}

TEST_F(ApiTest, DeleteRemovesTheVehicle) {
  auto res = del("/api/vehicles/rover");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 204);
  EXPECT_TRUE(res->body.empty());
  ASSERT_EQ(backend_.applied().size(), 1U);
  EXPECT_EQ(std::get<RemoveVehicle>(backend_.applied()[0]).name, "rover");
  EXPECT_EQ(get("/api/vehicles/rover")->status, 404);
  EXPECT_EQ(body_json(get("/api/vehicles")).size(), 1U);
  auto again = del("/api/vehicles/rover");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 404);
}

TEST_F(ApiTest, OversizedBodiesAreRefused) {
  const std::string huge = R"({"name":"x","body":")" + std::string(70 * 1024, 'a') + R"("})";
  auto res = post("/api/vehicles", huge);
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 413);
  EXPECT_TRUE(backend_.applied().empty());
}

}  // namespace
}  // namespace mocaplink::web::testing

// The request bodies of POST / PATCH /api/vehicles → the typed keys of a [[vehicle]] table. Only
// the API's own rules are checked here (JSON, object, known keys, `paused`, JSON types); values,
// ranges and spellings are the configuration's (tests/libs/config/add_vehicle_test.cpp).
#include "mocaplink/web/vehicle_request.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::web {
namespace {

using Value = config::VehicleKey::Value;

TEST(VehicleRequest, PostKeysKeepTheirJsonTypes) {
  const auto add = parse_vehicle_spec(
      R"({"name": "q2", "body": "Quad 2", "link": "udp://h:1", "system_id": 2, "rate_hz": 30.5,
          "messages": ["odometry"], "profile": "custom", "signing_key": "", "paused": true})");
  ASSERT_TRUE(add.ok()) << add.error().error;
  EXPECT_EQ(add.value().name, "q2");
  EXPECT_TRUE(add.value().paused);
  std::vector<std::string> keys;
  for (const auto& k : add.value().keys) keys.push_back(k.key);
  // nlohmann::json keeps object keys sorted; `paused` is not a [[vehicle]] key.
  EXPECT_EQ(keys, (std::vector<std::string>{"body", "link", "messages", "name", "profile",
                                            "rate_hz", "signing_key", "system_id"}));
  const auto& k = add.value().keys;
  EXPECT_EQ(k[2].value, Value(std::vector<std::string>{"odometry"}));
  EXPECT_EQ(k[5].value, Value(30.5));
  EXPECT_EQ(k[7].value, Value(std::int64_t{2}));
}

TEST(VehicleRequest, ValuesAreLeftToTheConfiguration) {
  // Out of range, misspelt, mistyped for the key: all passed on for config::add_vehicle to judge.
  const auto add = parse_vehicle_spec(
      R"({"name": "bad name", "rate_hz": 9000, "system_id": "7", "profile": "px5",
          "messages": "odometry"})");
  ASSERT_TRUE(add.ok()) << add.error().error;
  EXPECT_EQ(add.value().keys.size(), 5U);
  EXPECT_EQ(add.value().name, "bad name");
  // Missing keys: the configuration says which. The API defaults system_id and profile, which a
  // [[vehicle]] table must give.
  const auto empty = parse_vehicle_spec("{}");
  ASSERT_TRUE(empty.ok());
  ASSERT_EQ(empty.value().keys.size(), 2U);
  EXPECT_EQ(empty.value().keys[0].key, "system_id");
  EXPECT_EQ(empty.value().keys[0].value, Value(std::int64_t{1}));
  EXPECT_EQ(empty.value().keys[1].key, "profile");
  EXPECT_EQ(empty.value().keys[1].value, Value(std::string("px4")));
  // A huge unsigned integer becomes a number (out of every range, but not a wrapped one).
  const auto huge = parse_vehicle_spec(R"({"system_id": 18446744073709551615, "profile": "px4"})");
  ASSERT_TRUE(huge.ok());
  EXPECT_EQ(huge.value().keys[1].value, Value(18446744073709551615.0));  // keys sorted
}

TEST(VehicleRequest, TheApiRefusesWhatNoVehicleKeyCanBe) {
  struct Case {
    const char* body;
    int status;
    const char* field;
    const char* error;
  };
  const std::vector<Case> cases = {
      {"{", 400, "", "request body is not valid JSON"},
      {"[]", 400, "", "request body must be a JSON object"},
      {R"({"rate": 5})", 422, "rate", "rate: unknown key (did you mean \"rate_hz\"?)"},
      {R"({"component_id": 5})", 422, "component_id", "component_id: unknown key"},
      {R"({"paused": "yes"})", 422, "paused", "paused: must be true or false"},
      {R"({"body": null})", 422, "body",
       "body: expected a string, a number, true or false, or an array of strings, got null"},
      {R"({"link": {"host": "h"}})", 422, "link", "link: expected a string"},
      {R"({"messages": ["odometry", 3]})", 422, "messages", "messages: expected a string"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.body);
    const auto add = parse_vehicle_spec(c.body);
    ASSERT_FALSE(add.ok());
    EXPECT_EQ(add.error().status, c.status);
    EXPECT_EQ(add.error().field, c.field);
    EXPECT_EQ(add.error().error.rfind(c.error, 0), 0U) << add.error().error;
  }
}

TEST(VehicleRequest, PatchTakesRateMessagesAndPausedOnly) {
  const auto update =
      parse_vehicle_patch(R"({"rate_hz": 60, "messages": [], "paused": false})", "quad1");
  ASSERT_TRUE(update.ok()) << update.error().error;
  EXPECT_EQ(update.value().name, "quad1");
  EXPECT_EQ(update.value().paused, false);
  ASSERT_EQ(update.value().keys.size(), 2U);
  EXPECT_EQ(update.value().keys[0].key, "messages");
  EXPECT_EQ(update.value().keys[0].value, Value(std::vector<std::string>{}));
  EXPECT_EQ(update.value().keys[1].key, "rate_hz");
  EXPECT_EQ(update.value().keys[1].value, Value(std::int64_t{60}));

  const auto pause_only = parse_vehicle_patch(R"({"paused": true})", "quad1");
  ASSERT_TRUE(pause_only.ok());
  EXPECT_TRUE(pause_only.value().keys.empty());

  const auto profile = parse_vehicle_patch(R"({"profile": "px4"})", "quad1");
  ASSERT_FALSE(profile.ok());
  EXPECT_EQ(profile.error().field, "profile");
  const auto empty = parse_vehicle_patch("{}", "quad1");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().error, "nothing to change: give rate_hz, messages or paused");
}

TEST(VehicleRequest, ConfigurationRefusalsNameTheKey) {
  const ApiError keyed = refusal({"POST /api/vehicles", 0, 0, "rate_hz", "must be above 0"});
  EXPECT_EQ(keyed.status, 422);
  EXPECT_EQ(keyed.error, "rate_hz: must be above 0");
  EXPECT_EQ(keyed.field, "rate_hz");
  const ApiError whole = refusal({"POST /api/vehicles", 0, 0, "", "no vehicle named \"x\""});
  EXPECT_EQ(whole.error, "no vehicle named \"x\"");
  EXPECT_EQ(whole.field, "");
}

}  // namespace
}  // namespace mocaplink::web

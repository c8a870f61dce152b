// POST /api/vehicles/NAME/setup over real HTTP (issue 28): the body's two forms, every malformed
// one refused before the backend sees it, the backend's refusals passed on as 409, and the set-up
// fields of GET /api/vehicles/NAME (the fake backend holds a PX4 1.14 list, fake_backend.cpp).
#include <variant>

#include "api_fixture.hpp"

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

TEST_F(ApiTest, VehicleShowsItsSetup) {
  auto res = get("/api/vehicles/quad1");
  ASSERT_TRUE(res);
  const json v = body_json(res);
  EXPECT_EQ(v["autopilot"],
            (json{{"name", "px4"}, {"version", "1.14.3"}, {"profile_in_effect", "px4"}}));
  EXPECT_EQ(v["setup"]["state"], "blocked");
  ASSERT_EQ(v["setup"]["items"].size(), 3U);
  const json& ev = v["setup"]["items"][0];
  EXPECT_EQ(ev["parameter"], "EKF2_EV_CTRL");
  EXPECT_EQ(ev["current"], 0.0);
  EXPECT_EQ(ev["severity"], "blocks");
  EXPECT_EQ(ev["status"], "wrong");
  EXPECT_EQ(ev["fix"], 15.0);
  EXPECT_TRUE(v["setup"]["items"][2]["fix"].is_null());
  EXPECT_EQ(v["statustext"][0]["severity"], "warning");
  EXPECT_EQ(v["estimator"]["problems"], json::array({"no horizontal position"}));
  EXPECT_EQ(v["delay_ms"]["parameter"], "EKF2_EV_DELAY");
  EXPECT_TRUE(v["origin"].contains("advice"));
  // A vehicle nothing is known of yet: its list is waiting, its autopilot unknown.
  const json rover = body_json(get("/api/vehicles/rover"));
  EXPECT_EQ(rover["setup"]["state"], "waiting");
  EXPECT_EQ(rover["autopilot"]["name"], "unknown");
  EXPECT_TRUE(rover["autopilot"]["version"].is_null());
  EXPECT_TRUE(rover["estimator"].is_null());
}

TEST_F(ApiTest, SetupApplyWritesTheNamedFixes) {
  auto res = post("/api/vehicles/quad1/setup", R"({"apply": ["EKF2_EV_CTRL"]})");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json v = body_json(res);
  EXPECT_EQ(v["setup"]["items"][0]["apply"], "confirmed");
  const auto applied = backend_.applied();
  ASSERT_EQ(applied.size(), 1U);
  const auto* setup = std::get_if<SetupVehicle>(&applied[0]);
  ASSERT_NE(setup, nullptr);
  EXPECT_EQ(setup->name, "quad1");
  EXPECT_EQ(setup->apply, std::vector<std::string>{"EKF2_EV_CTRL"});
  EXPECT_FALSE(setup->reboot);
}

TEST_F(ApiTest, SetupRefusals) {
  const std::vector<std::pair<std::string, int>> bad{
      {R"({})", 422},
      {R"({"apply": []})", 422},
      {R"({"apply": "EKF2_EV_CTRL"})", 422},
      {R"({"apply": ["ekf2_ev_ctrl"]})", 422},                // names as the list spells them
      {R"({"apply": ["EKF2_EV_CTRL_TOO_LONG_NAME"]})", 422},  // > 16 characters
      {R"({"apply": [15]})", 422},
      {R"({"reboot": false})", 422},
      {R"({"reboot": true, "apply": ["EKF2_EV_CTRL"]})", 422},
      {R"({"rebot": true})", 422},
      {R"([1])", 400},
      {R"(not json)", 400},
      // Refused by the backend (as core::VehicleSetup would): not a wrong item of the list.
      {R"({"apply": ["EKF2_GPS_CTRL"]})", 409},
      {R"({"apply": ["COM_ARM_WO_GPS"]})", 409},
  };
  for (const auto& [body, status] : bad) {
    auto res = post("/api/vehicles/quad1/setup", body);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, status) << body << " → " << res->body;
    EXPECT_TRUE(body_json(res).contains("error")) << body;
  }
  EXPECT_TRUE(backend_.applied().empty());
  // The rover is armed (fake_backend.cpp): nothing is written to it.
  auto armed = post("/api/vehicles/rover/setup", R"({"reboot": true})");
  ASSERT_TRUE(armed);
  EXPECT_EQ(armed->status, 409) << armed->body;
  auto unknown = post("/api/vehicles/nobody/setup", R"({"reboot": true})");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  auto get_setup = get("/api/vehicles/quad1/setup");
  ASSERT_TRUE(get_setup);
  EXPECT_EQ(get_setup->status, 405);
  EXPECT_EQ(get_setup->get_header_value("Allow"), "POST");
  EXPECT_TRUE(backend_.applied().empty());
}

}  // namespace
}  // namespace mocaplink::web::testing

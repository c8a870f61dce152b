// GET /, the embedded assets, GET /api/status and GET /api/vehicles over real HTTP.
#include <fstream>
#include <sstream>

#include "api_fixture.hpp"

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

std::string read_source_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);  // tests run in the source tree (mocaplink_gtest)
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(ApiTest, RootServesTheEmbeddedPageByteForByte) {
  auto res = get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_EQ(res->body, read_source_file("web/index.html"));
  EXPECT_NE(res->get_header_value("Content-Security-Policy").find("default-src 'self'"),
            std::string::npos);
}

TEST_F(ApiTest, ScriptAndStyleAreServedWithTheirTypes) {
  auto js = get("/app.js");
  ASSERT_TRUE(js);
  EXPECT_EQ(js->status, 200);
  EXPECT_EQ(js->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  EXPECT_EQ(js->body, read_source_file("web/app.js"));
  auto css = get("/style.css");
  ASSERT_TRUE(css);
  EXPECT_EQ(css->get_header_value("Content-Type"), "text/css; charset=utf-8");
}

TEST_F(ApiTest, UnknownPagesAre404) {
  auto res = get("/missing.html");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  auto api = get("/api/nothing");
  ASSERT_TRUE(api);
  EXPECT_EQ(api->status, 404);
  EXPECT_EQ(body_json(api)["error"], "not found");
}

TEST_F(ApiTest, StatusHasTheDocumentedShapeAndTheBackendsValues) {
  backend_.set_time(3.0);  // Body1 is a quarter lap round its 1.5 m circle: (0, 1.5, 1)
  auto res = get("/api/status");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  const json s = body_json(res);
  EXPECT_DOUBLE_EQ(s["uptime_s"].get<double>(), 3.0);

  const json& station = s["station"];
  EXPECT_EQ(station["source"], "sim://?bodies=3");
  EXPECT_EQ(station["connected"], true);
  EXPECT_EQ(station["error"], "");
  EXPECT_DOUBLE_EQ(station["frame_rate_hz"].get<double>(), 199.7);
  EXPECT_DOUBLE_EQ(station["nominal_rate_hz"].get<double>(), 200.0);
  EXPECT_DOUBLE_EQ(station["latency_ms"].get<double>(), 2.4);
  EXPECT_DOUBLE_EQ(station["jitter_ms"].get<double>(), 0.3);
  EXPECT_EQ(station["frames"], 600);
  EXPECT_EQ(station["dropped"], 3);
  EXPECT_EQ(station["bridge_latency_ms"],
            (json{{"last", 0.12}, {"p50", 0.1}, {"p99", 0.45}, {"max", 0.9}}));
  EXPECT_EQ(station["late_frames_skipped"], 5);
  EXPECT_EQ(station["superseded_frames"], 7);
  EXPECT_EQ(station["rejected"], 2);
  EXPECT_EQ(station["rejected_reason"],
            "malformed datagram at byte 80: trailing non-zero bytes after 1 item");
  ASSERT_EQ(station["bodies"].size(), 3U);
  const json& body1 = station["bodies"][0];
  EXPECT_EQ(body1["name"], "Body1");
  EXPECT_EQ(body1["state"], "tracking");
  EXPECT_EQ(body1["tracked"], true);
  EXPECT_EQ(body1["mirrored"], false);
  ASSERT_EQ(body1["p_m"].size(), 3U);
  EXPECT_NEAR(body1["p_m"][0].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(body1["p_m"][1].get<double>(), 1.5, 1e-12);
  EXPECT_NEAR(body1["p_m"][2].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(body1["q_wxyz"], json::array({1.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(body1["frames_tracked"], 600);
  EXPECT_EQ(body1["rejected"], 0);
  EXPECT_EQ(body1["resets"], 0);
  EXPECT_EQ(station["bodies"][1]["rejected"], 2);
  EXPECT_EQ(station["bodies"][2]["state"], "lost");
  EXPECT_EQ(station["bodies"][2]["tracked"], false);

  ASSERT_EQ(s["vehicles"].size(), 2U);
  const json& quad = s["vehicles"][0];
  EXPECT_EQ(quad["name"], "quad1");
  EXPECT_EQ(quad["body"], "Body1");
  EXPECT_EQ(quad["link"], "udp://127.0.0.1:14540");
  EXPECT_EQ(quad["system_id"], 1);
  EXPECT_EQ(quad["profile"], "px4");
  EXPECT_EQ(quad["messages"], json::array({"odometry"}));
  EXPECT_EQ(quad["available_messages"].size(), 7U);
  EXPECT_DOUBLE_EQ(quad["rate_hz"].get<double>(), 50.0);
  EXPECT_EQ(quad["paused"], false);
  EXPECT_EQ(quad["link_state"], "up");
  EXPECT_DOUBLE_EQ(quad["last_heard_s"].get<double>(), 0.2);
  EXPECT_EQ(quad["sent"]["ODOMETRY"], 150);  // 3 s at 50 Hz
  EXPECT_EQ(quad["sent"]["HEARTBEAT"], 3);
  EXPECT_EQ(quad["sent_total"], 153);
  EXPECT_TRUE(quad["send_rate_hz"].is_number());
  EXPECT_EQ(quad["heartbeat"], (json{{"type", "quadrotor"},
                                     {"autopilot", "px4"},
                                     {"armed", false},
                                     {"mode", "POSCTL"},
                                     {"age_s", 0.2}}));
  EXPECT_EQ(quad["timesync"], (json{{"state", "synced"}, {"offset_ms", 1234.5}, {"rtt_ms", 0.8}}));
  EXPECT_EQ(quad["origin"], (json{{"state", "confirmed"}, {"advice", nullptr}}));
  EXPECT_EQ(quad["agreement"], (json{{"verdict", "agree"},
                                     {"tilt_offset_deg", 1.5},
                                     {"yaw_offset_deg", 0.4},
                                     {"position_offset_m", 0.012},
                                     {"heading_offset_deg", nullptr},
                                     {"checked", {"tilt", "yaw", "position"}},
                                     {"reason", nullptr},
                                     {"fix", nullptr}}));
  const json& rover = s["vehicles"][1];
  EXPECT_EQ(rover["timesync"]["state"], "off");
  EXPECT_TRUE(rover["timesync"]["offset_ms"].is_null());
  EXPECT_EQ(rover["origin"]["state"], "sending");
  EXPECT_EQ(rover["agreement"]["verdict"], "disagree");
}

TEST_F(ApiTest, StatusCarriesTheDerivedAlerts) {
  const json alerts = body_json(get("/api/status"))["alerts"];
  auto has = [&](const std::string& kind, const std::string& subject, const std::string& level) {
    for (const json& a : alerts) {
      if (a["kind"] == kind && a["subject"] == subject && a["level"] == level) return true;
    }
    return false;
  };
  EXPECT_TRUE(has("body_lost", "Body3", "warning")) << alerts.dump();  // no vehicle follows it
  EXPECT_TRUE(has("origin_not_confirmed", "rover", "warning")) << alerts.dump();
  EXPECT_TRUE(has("agreement_failing", "rover", "error")) << alerts.dump();
  EXPECT_TRUE(has("setup_blocked", "quad1", "error")) << alerts.dump();  // EKF2_EV_CTRL 0
  EXPECT_EQ(alerts.size(), 4U) << alerts.dump();
}

TEST_F(ApiTest, VehiclesListAndOneVehicle) {
  auto list = get("/api/vehicles");
  ASSERT_TRUE(list);
  EXPECT_EQ(list->status, 200);
  const json vehicles = body_json(list);
  ASSERT_EQ(vehicles.size(), 2U);
  EXPECT_EQ(vehicles[1]["name"], "rover");
  auto one = get("/api/vehicles/rover");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->status, 200);
  EXPECT_EQ(body_json(one)["profile"], "custom");
  auto none = get("/api/vehicles/nobody");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 404);
  EXPECT_EQ(body_json(none)["field"], "");
}

TEST_F(ApiTest, WrongMethodsAre405WithAllow) {
  auto status = post("/api/status", "{}");
  ASSERT_TRUE(status);
  EXPECT_EQ(status->status, 405);
  EXPECT_EQ(status->get_header_value("Allow"), "GET");
  auto vehicles = client_->Put("/api/vehicles", "{}", "application/json");
  ASSERT_TRUE(vehicles);
  EXPECT_EQ(vehicles->status, 405);
  EXPECT_EQ(vehicles->get_header_value("Allow"), "GET, POST");
  auto one = post("/api/vehicles/quad1", "{}");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->status, 405);
  EXPECT_EQ(body_json(one)["field"], "");
}

}  // namespace
}  // namespace mocaplink::web::testing

// Alert rules (alerts.hpp), one scenario each, with hand-made statuses.
#include <gtest/gtest.h>

#include "mocaplink/web/alerts.hpp"

namespace mocaplink::web {
namespace {

StatusView healthy() {
  StatusView s;
  s.station.source = "vicon://10.0.0.3";
  s.station.connected = true;
  s.station.bodies = {BodyView{.name = "Quad1", .state = core::TrackingState::tracking},
                      BodyView{.name = "Wand", .state = core::TrackingState::tracking}};
  VehicleView v;
  v.name = "quad1";
  v.body = "Quad1";
  v.link = "udp://10.0.0.21:14540";
  v.link_state = LinkHealth::up;
  v.origin = OriginState::confirmed;
  v.agreement.verdict = AgreementVerdict::agree;
  s.vehicles = {v};
  return s;
}

std::vector<std::string> kinds(const StatusView& s) {
  std::vector<std::string> out;
  for (const Alert& a : s.alerts)
    out.push_back(a.kind + "/" + a.subject + "/" + std::string(to_string(a.level)));
  return out;
}

TEST(Alerts, AHealthyLabHasNone) {
  AlertMonitor monitor;
  StatusView s = healthy();
  monitor.annotate(s, 0.0);
  EXPECT_TRUE(s.alerts.empty());
}

TEST(Alerts, EachConditionRaisesItsAlert) {
  AlertMonitor monitor;
  StatusView s = healthy();
  s.station.connected = false;
  s.station.error = "connection refused";
  s.station.bodies[0].state = core::TrackingState::lost;  // followed by quad1: error
  s.station.bodies[1].state = core::TrackingState::lost;  // followed by nobody: warning
  s.vehicles[0].origin = OriginState::sending;
  s.vehicles[0].agreement.verdict = AgreementVerdict::disagree;
  s.vehicles.push_back(s.vehicles[0]);
  s.vehicles[1].name = "rover";
  s.vehicles[1].link_state = LinkHealth::silent;
  s.vehicles[1].origin = OriginState::not_needed;
  s.vehicles[1].agreement.verdict = AgreementVerdict::unknown;
  s.vehicles.push_back(s.vehicles[1]);
  s.vehicles[2].name = "boat";
  s.vehicles[2].link_state = LinkHealth::down;
  s.alerts.push_back(Alert{AlertLevel::warning, "daemon_note", "x", "kept first"});
  monitor.annotate(s, 0.0);
  EXPECT_EQ(kinds(s), (std::vector<std::string>{
                          "daemon_note/x/warning", "source_disconnected/station/error",
                          "body_lost/Quad1/error", "body_lost/Wand/warning",
                          "origin_not_confirmed/quad1/warning", "agreement_failing/quad1/error",
                          "vehicle_silent/rover/warning", "link_down/boat/error"}));
  EXPECT_EQ(s.alerts[1].message, "No frames from vicon://10.0.0.3: connection refused");
}

TEST(Alerts, AMirroredBodyIsAnErrorWhenAVehicleFollowsIt) {
  AlertMonitor monitor;
  StatusView s = healthy();
  s.station.bodies[0].mirrored = true;  // followed by quad1
  s.station.bodies[1].mirrored = true;
  monitor.annotate(s, 0.0);
  EXPECT_EQ(kinds(s),
            (std::vector<std::string>{"body_mirrored/Quad1/error", "body_mirrored/Wand/warning"}));
  EXPECT_EQ(s.alerts[0].message,
            "Quad1's rotation from the source is mirrored (left-handed): no axis setting can fix "
            "it; check the handedness of the mocap system's frame");
}

TEST(Alerts, DropsRisingLooksBackOverTheWindow) {
  AlertMonitor monitor(AlertRules{.drops_window_s = 10.0});
  auto at = [&](double t, std::uint64_t dropped) {
    StatusView s = healthy();
    s.station.dropped = dropped;
    monitor.annotate(s, t);
    return s.alerts.empty() ? std::string() : s.alerts[0].message;
  };
  EXPECT_EQ(at(0.0, 5), "");  // old drops from before we looked are not "rising"
  EXPECT_EQ(at(1.0, 5), "");
  EXPECT_EQ(at(2.0, 8), "3 mocap frames dropped in the last 10 s");
  EXPECT_EQ(at(11.5, 8), "3 mocap frames dropped in the last 10 s");  // t=2 still inside
  EXPECT_EQ(at(12.5, 8), "");  // the rise at t=2 has left the window
  EXPECT_EQ(at(12.0, 9), "1 mocap frames dropped in the last 10 s");  // time going back: clamped
}

}  // namespace
}  // namespace mocaplink::web

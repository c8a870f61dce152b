// Bridge snapshot → StatusView: field mapping, measured send rate, MAVLink names and modes.
#include <gtest/gtest.h>

#include "mocaplink/web/bridge_views.hpp"

namespace mocaplink::web {
namespace {

using core::host_time_from_ns;

core::BridgeSnapshot snapshot_at(double t_s, std::uint64_t odometry_sent) {
  core::BridgeSnapshot s;
  s.time = host_time_from_ns(static_cast<std::int64_t>(t_s * 1e9));
  s.station.connected = true;
  core::StationBody body;
  body.name = "Quad1";
  body.tracked = true;
  body.ever_tracked = true;
  s.station.bodies.push_back(body);
  core::BodySnapshot estimate;
  estimate.name = "Quad1";
  estimate.estimate.state = core::TrackingState::lost;
  estimate.estimate.counters.rejected_outliers = 3;
  s.bodies.push_back(estimate);
  core::VehicleStatus v;
  v.name = "quad1";
  v.body = "Quad1";
  v.profile = core::Profile::px4;
  v.sender.system_id = 7;
  v.sender.messages = core::MessageSet{core::MessageKind::odometry};
  v.sender.rate_hz = 50.0;
  v.sender.counters.sent[static_cast<std::size_t>(core::MessageKind::odometry)] = odometry_sent;
  v.sender.counters.heartbeats = 2;
  v.sender.counters.frames = odometry_sent + 2;
  v.vehicle.link = core::LinkState::alive;
  v.vehicle.heartbeat = core::VehicleHeartbeat{1, 2, 12, 128 | 1, 3U << 16, 4, true};
  v.vehicle.last_heartbeat = host_time_from_ns(0);
  v.vehicle.last_message = host_time_from_ns(0);
  v.vehicle.origin = core::OriginState::conflict;
  v.vehicle.timesync = core::TimesyncEstimate{2'500'000, 800'000, 3};
  v.vehicle.agreement.verdict = core::AgreementVerdict::disagree;
  v.vehicle.agreement.yaw_offset_deg = 90.0;
  s.vehicles.push_back(v);
  return s;
}

TEST(BridgeViews, BridgeLatencyInMilliseconds) {
  BridgeStatusBuilder builder(host_time_from_ns(0));
  BridgeStatusContext context{"sim://", "", {"udp://127.0.0.1:14550"}, {}};
  EXPECT_FALSE(builder.build(snapshot_at(2.0, 100), context).station.bridge_latency_ms);
  using std::chrono::microseconds;
  context.bridge_latency = core::LatencySummary{microseconds(120), microseconds(100),
                                                microseconds(450), microseconds(900), 10};
  const auto latency = builder.build(snapshot_at(2.1, 100), context).station.bridge_latency_ms;
  ASSERT_TRUE(latency);
  EXPECT_DOUBLE_EQ(latency->last, 0.12);
  EXPECT_DOUBLE_EQ(latency->p50, 0.1);
  EXPECT_DOUBLE_EQ(latency->p99, 0.45);
  EXPECT_DOUBLE_EQ(latency->max, 0.9);
}

TEST(BridgeViews, LateFramesSkippedFromTheDaemon) {
  BridgeStatusBuilder builder(host_time_from_ns(0));
  BridgeStatusContext context{"sim://", "", {"udp://127.0.0.1:14550"}, {}};
  EXPECT_EQ(builder.build(snapshot_at(2.0, 100), context).station.late_frames_skipped, 0U);
  context.late_frames_skipped = 42;
  EXPECT_EQ(builder.build(snapshot_at(2.1, 100), context).station.late_frames_skipped, 42U);
}

TEST(BridgeViews, MapsEveryField) {
  BridgeStatusBuilder builder(host_time_from_ns(0));
  const BridgeStatusContext context{"sim://", "", {"udp://127.0.0.1:14550"}, {}};
  const StatusView s = builder.build(snapshot_at(2.0, 100), context);
  EXPECT_DOUBLE_EQ(s.uptime_s, 2.0);
  EXPECT_EQ(s.station.source, "sim://");
  ASSERT_EQ(s.station.bodies.size(), 1U);
  EXPECT_EQ(s.station.bodies[0].state, core::TrackingState::lost);  // the Tracker's word
  EXPECT_EQ(s.station.bodies[0].rejected, 3U);
  ASSERT_EQ(s.vehicles.size(), 1U);
  const VehicleView& v = s.vehicles[0];
  EXPECT_EQ(v.link, "udp://127.0.0.1:14550");
  EXPECT_EQ(v.system_id, 7);
  EXPECT_EQ(v.profile, "px4");
  EXPECT_EQ(v.messages, std::vector<std::string>{"odometry"});
  EXPECT_EQ(v.available_messages.size(), 7U);
  EXPECT_EQ(v.sent.at("ODOMETRY"), 100U);
  EXPECT_EQ(v.sent.at("HEARTBEAT"), 2U);
  EXPECT_EQ(v.sent_total, 102U);
  EXPECT_EQ(v.link_state, LinkState::up);
  EXPECT_DOUBLE_EQ(*v.last_heard_s, 2.0);
  ASSERT_TRUE(v.heartbeat.has_value());
  EXPECT_EQ(v.heartbeat->type, "quadrotor");
  EXPECT_EQ(v.heartbeat->autopilot, "px4");
  EXPECT_TRUE(v.heartbeat->armed);
  EXPECT_EQ(v.heartbeat->mode, "POSCTL");
  EXPECT_EQ(v.timesync.state, TimesyncState::synced);
  EXPECT_DOUBLE_EQ(*v.timesync.offset_ms, 2.5);
  EXPECT_DOUBLE_EQ(*v.timesync.rtt_ms, 0.8);
  EXPECT_EQ(v.origin, OriginState::conflict);
  EXPECT_EQ(v.agreement.verdict, AgreementVerdict::disagree);
  EXPECT_EQ(v.agreement.yaw_offset_deg, 90.0);

  const BridgeStatusContext down{"sim://", "refused", {"udp://x:1"}, {true}};
  EXPECT_EQ(builder.build(snapshot_at(2.1, 100), down).vehicles[0].link_state, LinkState::down);
}

TEST(BridgeViews, SendRateIsMeasuredOverAtLeastASecond) {
  BridgeStatusBuilder builder(host_time_from_ns(0));
  const BridgeStatusContext context{"sim://", "", {"udp://h:1"}, {}};
  EXPECT_DOUBLE_EQ(builder.build(snapshot_at(0.0, 0), context).vehicles[0].send_rate_hz, 0.0);
  EXPECT_DOUBLE_EQ(builder.build(snapshot_at(0.5, 25), context).vehicles[0].send_rate_hz, 0.0);
  // 1.25 s after the window start (t = 0): 100 poses → 80 Hz.
  EXPECT_DOUBLE_EQ(builder.build(snapshot_at(1.25, 100), context).vehicles[0].send_rate_hz, 80.0);
  // The window restarts at t = 1.25: until a second later the last figure stays.
  EXPECT_DOUBLE_EQ(builder.build(snapshot_at(1.5, 110), context).vehicles[0].send_rate_hz, 80.0);
  EXPECT_DOUBLE_EQ(builder.build(snapshot_at(2.25, 120), context).vehicles[0].send_rate_hz, 20.0);
}

TEST(BridgeViews, MavlinkNamesAndFlightModes) {
  EXPECT_EQ(mav_type_name(2), "quadrotor");
  EXPECT_EQ(mav_type_name(10), "ground_rover");
  EXPECT_EQ(mav_type_name(250), "250");
  EXPECT_EQ(mav_autopilot_name(3), "ardupilotmega");
  EXPECT_EQ(mav_autopilot_name(12), "px4");
  // PX4: main mode in byte 2, sub mode in byte 3 (px4_custom_mode.h).
  EXPECT_EQ(flight_mode_name(12, 2, 6U << 16), "OFFBOARD");
  EXPECT_EQ(flight_mode_name(12, 2, (4U << 16) | (4U << 24)), "AUTO_MISSION");
  EXPECT_EQ(flight_mode_name(12, 2, (4U << 16) | (6U << 24)), "AUTO_LAND");
  // ArduPilot: the number means different modes per vehicle type.
  EXPECT_EQ(flight_mode_name(3, 2, 4), "GUIDED");  // Copter
  EXPECT_EQ(flight_mode_name(3, 10, 4), "HOLD");   // Rover
  EXPECT_EQ(flight_mode_name(3, 1, 10), "AUTO");   // Plane
  EXPECT_EQ(flight_mode_name(0, 2, 7), "custom_mode 7");
}

}  // namespace
}  // namespace mocaplink::web

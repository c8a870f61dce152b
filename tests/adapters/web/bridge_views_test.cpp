// Bridge snapshot → StatusView: field mapping, the core's send rate, MAVLink names and modes.
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
  v.vehicle.link = core::HeartbeatState::alive;
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
  // The source's rejections pass through as the daemon read them.
  context.source_rejected = 7;
  context.source_rejected_reason = "datagram from 10.0.0.9, not 10.0.0.5 (from=)";
  const auto station = builder.build(snapshot_at(2.2, 100), context).station;
  EXPECT_EQ(station.rejected, 7U);
  EXPECT_EQ(station.rejected_reason, "datagram from 10.0.0.9, not 10.0.0.5 (from=)");
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
  EXPECT_EQ(v.link_state, LinkHealth::up);
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
  EXPECT_EQ(builder.build(snapshot_at(2.1, 100), down).vehicles[0].link_state, LinkHealth::down);
}

TEST(BridgeViews, AnUnknownAgreementSaysWhy) {
  // Issue 31: the dashboard says why there is no verdict instead of "waiting" forever.
  BridgeStatusBuilder builder(host_time_from_ns(0));
  const BridgeStatusContext context{"sim://", "", {"udp://h:1"}, {}};
  core::BridgeSnapshot s = snapshot_at(2.0, 100);
  core::VehicleStatus& in = s.vehicles[0];
  in.vehicle.agreement = core::Agreement{};
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "the mocap body Quad1 is not tracked");
  s.bodies[0].estimate.state = core::TrackingState::tracking;
  auto& attitude = in.streams.streams[static_cast<std::size_t>(core::VehicleStream::attitude)];
  attitude.state = core::StreamState::silent;
  attitude.asked = true;
  in.sender.counters.interval_requests = 4;
  in.sender.counters.data_stream_requests = 3;
  VehicleView v = builder.build(s, context).vehicles[0];
  EXPECT_EQ(v.agreement.reason,
            "no ATTITUDE from the vehicle after asking: is this port's MAVLink enabled?");
  // The estimator's named for the heartbeat's autopilot; not part of the agreement's reason.
  EXPECT_EQ(v.streams, (std::map<std::string, std::string>{{"ATTITUDE", "silent"},
                                                           {"ESTIMATOR_STATUS", "idle"},
                                                           {"LOCAL_POSITION_NED", "idle"}}));
  EXPECT_EQ(v.sent.at("SET_MESSAGE_INTERVAL"), 4U);
  EXPECT_EQ(v.sent.at("REQUEST_DATA_STREAM"), 3U);
  // Both messages arriving: the vehicle settling after its boot, then a disagreement on hold.
  for (auto& stream : in.streams.streams) stream.state = core::StreamState::arriving;
  // Issue 48: until the set-up list says where its yaw and position come from, no agreement.
  in.vehicle.agreement.sources.yaw = {core::EstimateSource::unknown, "EK3_SRC1_YAW"};
  in.vehicle.agreement.sources.position = {core::EstimateSource::independent, "EK3_SRC1_POSXY = 3"};
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "yaw not checkable yet: EK3_SRC1_YAW not read from the vehicle (does its yaw come from "
            "mocap?)");
  in.vehicle.agreement.sources.yaw = {core::EstimateSource::mocap, "EK3_SRC1_YAW = 6"};
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "comparing the vehicle's estimate with mocap");
  in.vehicle.agreement.settling = true;
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "the vehicle booted less than 15 s ago: its estimate is compared once it has settled");
  in.vehicle.agreement.settling = false;
  in.vehicle.agreement.disagreeing_since = host_time_from_ns(800'000'000);  // 1.2 s before
  EXPECT_EQ(
      builder.build(s, context).vehicles[0].agreement.reason,
      "the vehicle's estimate is beyond a threshold for 1.2 s: it disagrees if that lasts 3 s");
  in.vehicle.heartbeat.reset();
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "no HEARTBEAT from the vehicle yet");
  in.vehicle.agreement.verdict = core::AgreementVerdict::agree;
  // With a verdict the reason names what it did not measure.
  EXPECT_EQ(builder.build(s, context).vehicles[0].agreement.reason,
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6)");
  in.vehicle.agreement.sources.yaw = {core::EstimateSource::independent, "EK3_SRC1_YAW = 1"};
  EXPECT_FALSE(builder.build(s, context).vehicles[0].agreement.reason);
  EXPECT_FALSE(builder.build(s, context).vehicles[0].agreement.fix);
  // A disagreement names its fix, in the reason and as its own object.
  in.vehicle.agreement.verdict = core::AgreementVerdict::disagree;
  core::AxisFix fix;
  fix.kind = core::AxisFixKind::fix;
  fix.lines = {"[mocap] up = \"+z\""};
  fix.text = "fix: [mocap] up = \"+z\" (then tilt 0.0°)";
  in.vehicle.agreement.fix = fix;
  const VehicleView d = builder.build(s, context).vehicles[0];
  EXPECT_EQ(d.agreement.reason, "fix: [mocap] up = \"+z\" (then tilt 0.0°)");
  ASSERT_TRUE(d.agreement.fix);
  EXPECT_EQ(d.agreement.fix->kind, "fix");
  EXPECT_EQ(d.agreement.fix->lines, fix.lines);
}

TEST(BridgeViews, SendRateIsTheCoresWhateverWasAskedBefore) {
  // The core measures it over its fixed window (sender.hpp); the first view shows it as is.
  const BridgeStatusBuilder builder(host_time_from_ns(0));
  const BridgeStatusContext context{"sim://", "", {"udp://h:1"}, {}};
  core::BridgeSnapshot s = snapshot_at(0.5, 25);
  s.vehicles[0].sender.send_rate_hz = 49.5;
  EXPECT_DOUBLE_EQ(builder.build(s, context).vehicles[0].send_rate_hz, 49.5);
  EXPECT_DOUBLE_EQ(builder.build(s, context).vehicles[0].send_rate_hz, 49.5);
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

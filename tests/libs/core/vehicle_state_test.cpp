// VehicleState: heartbeat and link state, TIMESYNC answers and estimates, the origin state
// machine, and the agreement check (with a deliberate 90° yaw error).
#include "mocaplink/core/vehicle_state.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr double kPi = std::numbers::pi;
const GeodeticPosition kOrigin{47.3977418, 8.5455938, 488.0};

ReceivedMessage from(std::uint8_t sysid, std::uint8_t compid, mavlink::Message m) {
  return ReceivedMessage{sysid, compid, std::move(m)};
}

mavlink::Heartbeat autopilot_heartbeat(std::uint8_t autopilot, std::uint8_t base_mode = 0) {
  mavlink::Heartbeat hb;
  hb.type = 2;  // quadrotor
  hb.autopilot = autopilot;
  hb.base_mode = base_mode;
  hb.custom_mode = 0x00040000;
  hb.system_status = 3;
  return hb;
}

mavlink::GpsGlobalOrigin origin_report(std::int32_t lat, std::int32_t lon, std::int32_t alt_mm) {
  mavlink::GpsGlobalOrigin o;
  o.latitude = lat;
  o.longitude = lon;
  o.altitude = alt_mm;
  return o;
}

VehicleState with_origin() {
  VehicleStateConfig c;
  c.system_id = 1;
  c.origin = kOrigin;
  return VehicleState(c);
}

TEST(VehicleHeartbeat, ArmedModeAndSilence) {
  VehicleState v(VehicleStateConfig{});
  EXPECT_EQ(v.link_state(), LinkState::waiting);
  auto r = v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4, 128 | 1)),
                        HostTime{seconds(1)}, nullptr);
  EXPECT_TRUE(r.link_changed);
  auto s = v.snapshot();
  ASSERT_TRUE(s.heartbeat);
  EXPECT_TRUE(s.heartbeat->armed);
  EXPECT_EQ(s.heartbeat->autopilot, 12);
  EXPECT_EQ(s.heartbeat->custom_mode, 0x00040000U);
  EXPECT_EQ(s.heartbeat->type, 2);
  EXPECT_EQ(s.link, LinkState::alive);
  EXPECT_FALSE(v.on_tick(HostTime{seconds(4)}));  // exactly 3 s: still alive
  EXPECT_TRUE(v.on_tick(HostTime{seconds(4) + milliseconds(1)}));
  EXPECT_EQ(v.link_state(), LinkState::silent);
  r = v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4, 0)), HostTime{seconds(5)},
                   nullptr);
  EXPECT_TRUE(r.link_changed);
  EXPECT_FALSE(v.snapshot().heartbeat->armed);
}

TEST(VehicleHeartbeat, OthersDoNotCount) {
  VehicleState v(VehicleStateConfig{});
  mavlink::Heartbeat gcs = autopilot_heartbeat(8);
  gcs.type = 6;
  v.on_message(from(255, 190, gcs), HostTime{}, nullptr);                   // a GCS
  v.on_message(from(1, 197, autopilot_heartbeat(8)), HostTime{}, nullptr);  // a companion
  v.on_message(from(2, 1, autopilot_heartbeat(3)), HostTime{}, nullptr);    // another vehicle
  EXPECT_EQ(v.link_state(), LinkState::waiting);
  EXPECT_EQ(v.snapshot().counters.from_other_systems, 2U);
}

TEST(VehicleTimesync, RequestsAreAnsweredAtOnce) {
  VehicleState v(VehicleStateConfig{});
  mavlink::Timesync req;
  req.tc1 = 0;
  req.ts1 = 5'000'000'123;
  const auto r = v.on_message(from(1, 1, req), HostTime{seconds(42)}, nullptr);
  ASSERT_TRUE(r.timesync_reply);
  EXPECT_EQ(r.timesync_reply->tc1, 42'000'000'000);
  EXPECT_EQ(r.timesync_reply->ts1, 5'000'000'123);
  EXPECT_EQ(r.timesync_reply->target_system, 1);
  EXPECT_EQ(r.timesync_reply->target_component, 1);
  // Addressed to another system: not ours to answer.
  req.target_system = 9;
  EXPECT_FALSE(v.on_message(from(9, 1, req), HostTime{}, nullptr).timesync_reply);
  // A response to somebody else's request is not answered either.
  mavlink::Timesync resp;
  resp.tc1 = 77;
  resp.ts1 = 1234;
  EXPECT_FALSE(v.on_message(from(1, 1, resp), HostTime{}, nullptr).timesync_reply);
  EXPECT_FALSE(v.snapshot().timesync);
}

TEST(VehicleTimesync, OffsetAndRttFromOurRequests) {
  VehicleState v(VehicleStateConfig{});
  v.on_timesync_request_sent(10'000'000'000);  // sent at host 10 s
  mavlink::Timesync resp;
  resp.ts1 = 10'000'000'000;
  resp.tc1 = 500'004'000'000;  // vehicle clock 490 s ahead, read 4 ms after sending
  v.on_message(from(1, 1, resp), HostTime{seconds(10) + milliseconds(8)}, nullptr);
  const auto s = v.snapshot();
  ASSERT_TRUE(s.timesync);
  EXPECT_EQ(s.timesync->rtt_ns, 8'000'000);
  EXPECT_EQ(s.timesync->offset_ns, 490'000'000'000);
  EXPECT_EQ(s.timesync->samples, 1U);
  // The same response again is not counted twice.
  v.on_message(from(1, 1, resp), HostTime{seconds(11)}, nullptr);
  EXPECT_EQ(v.snapshot().timesync->samples, 1U);
}

TEST(VehicleOrigin, SendingUntilConfirmed) {
  VehicleState v = with_origin();
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  EXPECT_TRUE(v.wants_origin());
  // Within one degE7 and 1 cm: confirmed.
  const auto r =
      v.on_message(from(1, 1, origin_report(473977419, 85455937, 488010)), HostTime{}, nullptr);
  EXPECT_TRUE(r.origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::confirmed);
  EXPECT_FALSE(v.wants_origin());
}

TEST(VehicleOrigin, Px4MismatchKeepsSending) {
  VehicleState v = with_origin();
  v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4)), HostTime{}, nullptr);
  v.on_message(from(1, 1, origin_report(473977420, 85455938, 488000)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::sending);  // 2 degE7 off: not a match
  v.on_message(from(1, 1, origin_report(473977418, 85455938, 488011)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::sending);  // 11 mm off
  EXPECT_EQ(v.snapshot().counters.origin_mismatches, 2U);
  v.on_message(from(1, 1, origin_report(473977418, 85455938, 488000)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::confirmed);
}

TEST(VehicleOrigin, ArdupilotMismatchIsAConflict) {
  VehicleState v = with_origin();
  v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotArdupilot)), HostTime{}, nullptr);
  const auto r =
      v.on_message(from(1, 1, origin_report(-353632620, 1491652300, 584000)), HostTime{}, nullptr);
  EXPECT_TRUE(r.origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::conflict);
  EXPECT_FALSE(v.wants_origin());
  const auto s = v.snapshot();
  ASSERT_TRUE(s.reported_origin);
  EXPECT_NEAR(s.reported_origin->latitude_deg, -35.363262, 1e-9);
  EXPECT_NEAR(s.reported_origin->altitude_m, 584.0, 1e-9);
}

TEST(VehicleOrigin, NotNeededWithoutOrigin) {
  VehicleState v(VehicleStateConfig{});
  EXPECT_EQ(v.origin_state(), OriginState::not_needed);
  v.on_message(from(1, 1, origin_report(1, 2, 3)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::not_needed);
  EXPECT_TRUE(v.snapshot().reported_origin);
}

BodyEstimate mocap_at(Eigen::Vector3d p, double yaw_rad) {
  BodyEstimate e;
  e.state = TrackingState::tracking;
  e.last_outcome = SampleOutcome::accepted;
  e.p_ned_m = p;
  e.q_ned_frd = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
  return e;
}

mavlink::Attitude attitude(double yaw_rad) {
  mavlink::Attitude a;
  a.yaw = static_cast<float>(yaw_rad);
  return a;
}

mavlink::LocalPositionNed local(float x, float y, float z) {
  mavlink::LocalPositionNed p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

TEST(VehicleAgreement, AgreesWithinThresholds) {
  VehicleState v(VehicleStateConfig{});
  const auto mocap = mocap_at({1.0, 2.0, -0.5}, 10.0 * kPi / 180.0);
  v.on_message(from(1, 1, attitude(15.0 * kPi / 180.0)), HostTime{}, &mocap);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);  // position not known yet
  const auto r = v.on_message(from(1, 1, local(1.1F, 2.0F, -0.5F)), HostTime{}, &mocap);
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 5.0, 1e-4);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.1, 1e-6);
}

TEST(VehicleAgreement, DeliberateNinetyDegreeYawError) {
  VehicleState v(VehicleStateConfig{});
  // The rigid body was created nose-left: mocap says north (0°), the vehicle says east (90°).
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  v.on_message(from(1, 1, local(0.0F, 0.05F, -1.0F)), HostTime{}, &mocap);
  const auto r = v.on_message(from(1, 1, attitude(kPi / 2)), HostTime{seconds(1)}, &mocap);
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 90.0, 1e-4);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.05, 1e-6);
}

TEST(VehicleAgreement, YawWrapsAcross180) {
  VehicleState v(VehicleStateConfig{});
  const auto mocap = mocap_at({0.0, 0.0, 0.0}, 179.0 * kPi / 180.0);
  v.on_message(from(1, 1, attitude(-179.0 * kPi / 180.0)), HostTime{}, &mocap);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 2.0, 1e-4);  // not −358
  EXPECT_DOUBLE_EQ(wrap_deg_180(180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(540.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-190.0), 170.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-0.0), 0.0);
}

TEST(VehicleAgreement, PositionOffsetDisagreesAndLostMocapIsIgnored) {
  VehicleState v(VehicleStateConfig{});
  auto mocap = mocap_at({0.0, 0.0, 0.0}, 0.0);
  v.on_message(from(1, 1, attitude(0.0)), HostTime{}, &mocap);
  v.on_message(from(1, 1, local(0.0F, 0.4F, 0.0F)), HostTime{}, &mocap);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.4, 1e-6);
  mocap.state = TrackingState::lost;
  v.on_message(from(1, 1, local(0.0F, 0.0F, 0.0F)), HostTime{}, &mocap);  // ignored
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.4, 1e-6);
  v.on_message(from(1, 1, local(0.0F, 0.0F, 0.0F)), HostTime{}, nullptr);  // ignored
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
}

}  // namespace
}  // namespace mocaplink::core

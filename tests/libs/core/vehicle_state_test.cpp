// VehicleState: heartbeats and HeartbeatState, TIMESYNC answers and estimates, the origin state
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
  EXPECT_EQ(v.link_state(), HeartbeatState::waiting);
  auto r = v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4, 128 | 1)),
                        HostTime{seconds(1)}, nullptr);
  EXPECT_TRUE(r.link_changed);
  auto s = v.snapshot();
  ASSERT_TRUE(s.heartbeat);
  EXPECT_TRUE(s.heartbeat->armed);
  EXPECT_EQ(s.heartbeat->autopilot, 12);
  EXPECT_EQ(s.heartbeat->custom_mode, 0x00040000U);
  EXPECT_EQ(s.heartbeat->type, 2);
  EXPECT_EQ(s.link, HeartbeatState::alive);
  EXPECT_FALSE(v.on_tick(HostTime{seconds(4)}).link_changed);  // exactly 3 s: still alive
  EXPECT_TRUE(v.on_tick(HostTime{seconds(4) + milliseconds(1)}).link_changed);
  EXPECT_EQ(v.link_state(), HeartbeatState::silent);
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
  EXPECT_EQ(v.link_state(), HeartbeatState::waiting);
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

TEST(VehicleOrigin, GivenUpAfterThirtySecondsOfHeartbeats) {
  // PX4 1.14 without GPS never reports an origin (setup_rules.hpp, unconfirmed_origin_advice).
  VehicleState v = with_origin();
  // Without a heartbeat, time does not count.
  for (int s = 0; s <= 60; ++s) EXPECT_FALSE(v.on_tick(HostTime{seconds(s)}).origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  // Heartbeats from t = 100 s: 30 s later sending stops, once.
  int changes = 0;
  for (int ms = 100'000; ms <= 140'000; ms += 100) {
    if (ms % 500 == 0) {
      v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4)), HostTime{milliseconds(ms)},
                   nullptr);
    }
    if (v.on_tick(HostTime{milliseconds(ms)}).origin_changed) {
      ++changes;
      EXPECT_GE(ms, 100'000 + 30'000);
      EXPECT_LE(ms, 100'000 + 30'100);
    }
  }
  EXPECT_EQ(changes, 1);
  EXPECT_EQ(v.origin_state(), OriginState::unconfirmed);
  EXPECT_FALSE(v.wants_origin());
  // A matching report later still confirms it.
  v.on_message(from(1, 1, origin_report(473977418, 85455938, 488000)), HostTime{seconds(200)},
               nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::confirmed);
}

TEST(VehicleOrigin, SilenceRestartsTheCount) {
  VehicleState v = with_origin();
  const auto beat = [&](int s) {
    v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4)), HostTime{seconds(s)}, nullptr);
    v.on_tick(HostTime{seconds(s)});
  };
  for (int s = 0; s < 20; ++s) beat(s);
  v.on_tick(HostTime{seconds(30)});  // silent: nothing for more than 3 s
  for (int s = 40; s < 65; ++s) beat(s);
  EXPECT_EQ(v.origin_state(), OriginState::sending);  // 20 s + 25 s, never 30 s in a row
  for (int s = 65; s <= 71; ++s) beat(s);
  EXPECT_EQ(v.origin_state(), OriginState::unconfirmed);
}

TEST(VehicleOrigin, ARebootSendsItAgainWhateverItsState) {
  // Confirmed: ArduCopter SITL rebooted after a set-up lost its origin and never armed ("PreArm:
  // AHRS: waiting for home") while mocaplink still said confirmed and sent nothing.
  VehicleState v = with_origin();
  v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotArdupilot)), HostTime{}, nullptr);
  v.on_message(from(1, 1, origin_report(473977418, 85455938, 488000)), HostTime{}, nullptr);
  ASSERT_EQ(v.origin_state(), OriginState::confirmed);
  EXPECT_TRUE(v.on_reboot().origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  EXPECT_TRUE(v.wants_origin());
  EXPECT_FALSE(v.snapshot().reported_origin);  // the old boot's report is gone
  EXPECT_FALSE(v.on_reboot().origin_changed);  // already sending: no event
  // In conflict: a reboot is the remedy, so ours is sent again.
  v.on_message(from(1, 1, origin_report(-353632620, 1491652300, 584000)), HostTime{}, nullptr);
  ASSERT_EQ(v.origin_state(), OriginState::conflict);
  EXPECT_TRUE(v.on_reboot().origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  // Given up (PX4 1.14): another 30 s of sending after the reboot.
  for (int ms = 0; ms <= 31'000; ms += 100) {
    if (ms % 500 == 0) {
      v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4)), HostTime{milliseconds(ms)},
                   nullptr);
    }
    v.on_tick(HostTime{milliseconds(ms)});
  }
  ASSERT_EQ(v.origin_state(), OriginState::unconfirmed);
  EXPECT_TRUE(v.on_reboot().origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  // Without an [origin] there is nothing to send, reboot or not.
  VehicleState none(VehicleStateConfig{});
  EXPECT_FALSE(none.on_reboot().origin_changed);
  EXPECT_EQ(none.origin_state(), OriginState::not_needed);
}

TEST(VehicleOrigin, AWithheldOriginStaysWithheldUntilAReboot) {
  VehicleState v = with_origin();
  EXPECT_TRUE(v.withhold_origin().origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::withheld);
  EXPECT_FALSE(v.wants_origin());
  EXPECT_FALSE(v.withhold_origin().origin_changed);  // once
  // Another origin reported (a GPS fix of its own): still not ours to send.
  v.on_message(from(1, 1, autopilot_heartbeat(kMavAutopilotPx4)), HostTime{}, nullptr);
  v.on_message(from(1, 1, origin_report(1, 2, 3)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::withheld);
  // Ours reported after all: confirmed.
  v.on_message(from(1, 1, origin_report(473977418, 85455938, 488000)), HostTime{}, nullptr);
  EXPECT_EQ(v.origin_state(), OriginState::confirmed);
  // A reboot starts over (the gate decides again); a confirmed one is never withheld.
  EXPECT_FALSE(v.withhold_origin().origin_changed);
  EXPECT_TRUE(v.on_reboot().origin_changed);
  EXPECT_EQ(v.origin_state(), OriginState::sending);
  VehicleState none(VehicleStateConfig{});
  EXPECT_FALSE(none.withhold_origin().origin_changed);
  EXPECT_EQ(none.origin_state(), OriginState::not_needed);
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

/// A vehicle up for a minute unless told otherwise: past kAgreementSettle.
constexpr std::uint32_t kSettledBootMs = 60'000;

mavlink::Attitude attitude(double yaw_rad, std::uint32_t time_boot_ms = kSettledBootMs) {
  mavlink::Attitude a;
  a.time_boot_ms = time_boot_ms;
  a.yaw = static_cast<float>(yaw_rad);
  return a;
}

mavlink::LocalPositionNed local(float x, float y, float z,
                                std::uint32_t time_boot_ms = kSettledBootMs) {
  mavlink::LocalPositionNed p;
  p.time_boot_ms = time_boot_ms;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

HostTime at_ms(std::int64_t ms) {
  return HostTime{milliseconds(ms)};
}

/// ATTITUDE (yaw) and LOCAL_POSITION_NED every 200 ms (the 5 Hz mocaplink asks for) from
/// `from_ms` to `to_ms` of host time, the vehicle's boot clock `boot_offset_ms` behind; returns the
/// host time (ms) of the first verdict change to `watch`, or −1.
std::int64_t stream(VehicleState& v, const BodyEstimate& mocap, double yaw_rad, float y_m,
                    std::int64_t from_ms, std::int64_t to_ms, std::int64_t boot_offset_ms,
                    AgreementVerdict watch) {
  std::int64_t first = -1;
  for (std::int64_t t = from_ms; t <= to_ms; t += 200) {
    const auto boot = static_cast<std::uint32_t>(t - boot_offset_ms);
    for (const mavlink::Message& m : {mavlink::Message{attitude(yaw_rad, boot)},
                                      mavlink::Message{local(0.0F, y_m, -1.0F, boot)}}) {
      const auto r = v.on_message(from(1, 1, m), at_ms(t), &mocap);
      if (first < 0 && r.agreement_changed && v.agreement().verdict == watch) first = t;
    }
  }
  return first;
}

/// A vehicle whose yaw and position are its own (compass yaw, its own GPS): what the check
/// compares is independent of mocap, so it may agree (estimate_sources.hpp).
EstimateSources own_sensors() {
  return {{EstimateSource::independent, "EK3_SRC1_YAW = 1"},
          {EstimateSource::independent, "EK3_SRC1_POSXY = 3"}};
}

VehicleState checkable_vehicle() {
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(own_sensors(), HostTime{});
  return v;
}

TEST(VehicleAgreement, AgreesWithinThresholdsAtOnce) {
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({1.0, 2.0, -0.5}, 10.0 * kPi / 180.0);
  v.on_message(from(1, 1, attitude(15.0 * kPi / 180.0)), HostTime{}, &mocap);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);  // position not known yet
  const auto r = v.on_message(from(1, 1, local(1.1F, 2.0F, -0.5F)), HostTime{}, &mocap);
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 5.0, 1e-4);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.1, 1e-6);
  EXPECT_FALSE(v.agreement().disagreeing_since);
  EXPECT_FALSE(v.agreement().settling);
}

TEST(VehicleAgreement, DeliberateNinetyDegreeYawErrorIsFlaggedAfterTheHold) {
  VehicleState v = checkable_vehicle();
  // The rigid body was created nose-left: mocap says north (0°), the vehicle says east (90°).
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  v.on_message(from(1, 1, local(0.0F, 0.05F, -1.0F)), at_ms(0), &mocap);
  v.on_message(from(1, 1, attitude(kPi / 2)), at_ms(0), &mocap);
  // The offsets show at once; the verdict waits for kAgreementHold.
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 90.0, 1e-4);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.05, 1e-6);
  EXPECT_EQ(v.agreement().disagreeing_since, at_ms(0));
  const auto before = v.on_message(from(1, 1, attitude(kPi / 2)), at_ms(2'999), &mocap);
  EXPECT_FALSE(before.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  const auto r = v.on_message(from(1, 1, attitude(kPi / 2)), at_ms(3'000), &mocap);
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
  // A sustained one in a 5 Hz stream: flagged exactly kAgreementHold after it began.
  VehicleState w = checkable_vehicle();
  EXPECT_EQ(stream(w, mocap, kPi / 2, 0.0F, 10'000, 20'000, -60'000, AgreementVerdict::disagree),
            10'000 + std::chrono::duration_cast<milliseconds>(kAgreementHold).count());
}

TEST(VehicleAgreement, ADisagreementShorterThanTheHoldNeverDisagrees) {
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  // Agreeing, then 2.8 s of a 40° yaw jump (an EKF yaw reset), then agreeing again, twice.
  for (int round = 0; round < 2; ++round) {
    const std::int64_t t0 = round * 10'000;
    EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, t0, t0 + 2'000, -60'000, AgreementVerdict::disagree), -1);
    EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
    EXPECT_EQ(stream(v, mocap, 40.0 * kPi / 180.0, 0.0F, t0 + 2'200, t0 + 5'000, -60'000,
                     AgreementVerdict::disagree),
              -1);
    EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);  // not sure yet
    EXPECT_EQ(v.agreement().disagreeing_since, at_ms(t0 + 2'200));
    EXPECT_EQ(
        stream(v, mocap, 0.0, 0.0F, t0 + 5'200, t0 + 9'800, -60'000, AgreementVerdict::disagree),
        -1);
    EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);  // agreeing again: at once
    EXPECT_FALSE(v.agreement().disagreeing_since);
  }
}

TEST(VehicleAgreement, AfterBootTheEstimateSettlesBeforeItIsCompared) {
  // Issue 31: mocaplink on while the vehicle boots; its estimate is 90° and 1 m off for its first
  // 10 s of uptime (not converged), then right. No disagree, no alert, at any moment.
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  const std::int64_t boot = 5'000;  // host time of the vehicle's boot
  EXPECT_EQ(stream(v, mocap, kPi / 2, 1.0F, boot + 1'000, boot + 10'000, boot,
                   AgreementVerdict::disagree),
            -1);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  EXPECT_TRUE(v.agreement().settling);
  EXPECT_FALSE(v.agreement().yaw_offset_deg);  // not compared, not shown
  EXPECT_EQ(
      stream(v, mocap, 0.0, 0.0F, boot + 10'200, boot + 14'800, boot, AgreementVerdict::disagree),
      -1);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  // From 15 s of uptime on the estimate is compared: it agrees at once.
  const std::int64_t settled_ms =
      boot + std::chrono::duration_cast<milliseconds>(kAgreementSettle).count();
  EXPECT_EQ(
      stream(v, mocap, 0.0, 0.0F, boot + 15'000, boot + 16'000, boot, AgreementVerdict::agree),
      settled_ms);
  EXPECT_FALSE(v.agreement().settling);
}

TEST(VehicleAgreement, ARealMistakeRightAfterBootIsFlaggedOnceSettledAndHeld) {
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  // The body is defined 90° off: the vehicle boots at host time 0 and stays 90° off.
  EXPECT_EQ(stream(v, mocap, kPi / 2, 0.0F, 1'000, 30'000, 0, AgreementVerdict::disagree),
            std::chrono::duration_cast<milliseconds>(kAgreementSettle + kAgreementHold).count());
}

TEST(VehicleAgreement, ARebootRestartsTheCheck) {
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  EXPECT_GE(stream(v, mocap, kPi / 2, 0.0F, 0, 5'000, -60'000, AgreementVerdict::disagree), 0);
  // The vehicle reboots at 10 s (its boot clock starts again): unknown at once, not disagree.
  const auto r = v.on_message(from(1, 1, attitude(kPi / 2, 300)), at_ms(10'300), &mocap);
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  EXPECT_TRUE(v.agreement().settling);
  EXPECT_FALSE(v.agreement().disagreeing_since);
}

TEST(VehicleAgreement, YawWrapsAcross180) {
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, 0.0}, 179.0 * kPi / 180.0);
  v.on_message(from(1, 1, attitude(-179.0 * kPi / 180.0)), HostTime{}, &mocap);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 2.0, 1e-4);  // not −358
  EXPECT_DOUBLE_EQ(wrap_deg_180(180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(540.0), 180.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-190.0), 170.0);
  EXPECT_DOUBLE_EQ(wrap_deg_180(-0.0), 0.0);
}

TEST(VehicleAgreement, MocapComparedWithItselfNeverAgrees) {
  // Issue 48: ArduCopter with EKF3 yaw and position from ExternalNav reports mocaplink's own yaw
  // and position back; they match whatever the axes. Unknown while its parameters are unread,
  // and never agree on them alone.
  VehicleState v(VehicleStateConfig{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, 0, 2'000, -60'000, AgreementVerdict::agree), -1);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);  // the sources are not known
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 0.0, 1e-4);
  const EstimateSources external_nav{{EstimateSource::mocap, "EK3_SRC1_YAW = 6"},
                                     {EstimateSource::mocap, "EK3_SRC1_POSXY = 6"}};
  (void)v.set_estimate_sources(external_nav, at_ms(2'100));
  EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, 2'200, 6'000, -60'000, AgreementVerdict::agree), -1);
  EXPECT_EQ(v.agreement().sources, external_nav);
  // A mocap-fed yaw that does not follow mocap is still a real disagreement.
  EXPECT_EQ(stream(v, mocap, kPi / 2, 0.0F, 6'200, 10'000, -60'000, AgreementVerdict::disagree),
            9'200);
}

TEST(VehicleAgreement, SourcesLearntLaterJudgeTheVerdictAgain) {
  VehicleState v(VehicleStateConfig{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  (void)stream(v, mocap, 0.0, 0.0F, 0, 1'000, -60'000, AgreementVerdict::agree);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::unknown);
  const auto r = v.set_estimate_sources(own_sensors(), at_ms(1'100));
  EXPECT_TRUE(r.agreement_changed);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
  EXPECT_FALSE(v.set_estimate_sources(own_sensors(), at_ms(1'200)).agreement_changed);
}

TEST(VehicleAgreement, TiltIsTheGravityDirectionWithoutYaw) {
  // Mocap level with its nose east; the vehicle pitched 3° nose up (a sloped floor) and rolled
  // 2°: the gravity directions differ by acos(cos 3° cos 2°) = 3.6046°, whatever the yaw.
  VehicleState v = checkable_vehicle();
  const auto mocap = mocap_at({0.0, 0.0, 0.0}, kPi / 2);
  mavlink::Attitude a = attitude(kPi / 2);
  a.roll = static_cast<float>(2.0 * kPi / 180.0);
  a.pitch = static_cast<float>(3.0 * kPi / 180.0);
  v.on_message(from(1, 1, a), at_ms(0), &mocap);
  v.on_message(from(1, 1, local(0.0F, 0.0F, 0.0F)), at_ms(0), &mocap);
  const double want = std::acos(std::cos(3.0 * kPi / 180.0) * std::cos(2.0 * kPi / 180.0));
  EXPECT_NEAR(*v.agreement().tilt_offset_deg, want * 180.0 / kPi, 1e-4);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
}

TEST(VehicleAgreement, UpAxisMistakeWithExternalNavYawDisagreesOnGravity) {
  // Issue 48 as reported: a Z-up Vicon configured up = "+y", the vehicle level with its nose on
  // mocap +x, EKF3 yaw and position from ExternalNav (so both match mocap). By hand: the world
  // mapping's rows are N = +x, E = D x N = -y x +x = +z, D = -y; the body mapping FLU -> FRD is
  // diag(1, -1, -1); R_ned_frd = W * I * B = [[1,0,0],[0,0,-1],[0,1,0]]: mocap's body down is
  // its right (+y row 2): 90° of roll, where the vehicle's IMU says level.
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(
      {{EstimateSource::mocap, "EK3_SRC1_YAW = 6"}, {EstimateSource::mocap, "EK3_SRC1_POSXY = 6"}},
      HostTime{});
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  auto mocap = mocap_at({0.0, 0.0, 0.0}, 0.0);
  mocap.q_ned_frd = Eigen::Quaterniond(r);
  // The vehicle reports mocap's yaw (0: the nose's heading is unchanged by this mistake).
  EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, 0, 5'000, -60'000, AgreementVerdict::disagree), 3'000);
  EXPECT_NEAR(*v.agreement().tilt_offset_deg, 90.0, 1e-4);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 0.0, 1e-4);
}

/// ArduCopter with EKF3 yaw and position from ExternalNav and a calibrated compass: its field in
/// RAW_IMU is the nose's one reference (estimate_sources.hpp).
EstimateSources external_nav_with_compass() {
  EstimateSources s{{EstimateSource::mocap, "EK3_SRC1_YAW = 6"},
                    {EstimateSource::mocap, "EK3_SRC1_POSXY = 6"}};
  s.heading = {EstimateSource::independent,
               "its compass in RAW_IMU: COMPASS_ENABLE = 1, calibrated"};
  return s;
}

/// ArduPilot's RAW_IMU from a level vehicle whose nose is `heading_rad` east of magnetic north:
/// Earth's field 250 mG north, 450 mG down seen in the body frame, rounded as the int16 fields
/// are (so headings are good to ~0.2°).
mavlink::RawImu raw_imu(double heading_rad) {
  const auto mg = [](double v) { return static_cast<std::int16_t>(std::lround(v)); };
  mavlink::RawImu m;
  m.xmag = mg(250.0 * std::cos(heading_rad));
  m.ymag = mg(-250.0 * std::sin(heading_rad));
  m.zmag = mg(450.0);
  return m;
}

/// stream() with RAW_IMU at `heading_rad` before each ATTITUDE.
std::int64_t stream_with_heading(VehicleState& v, const BodyEstimate& mocap, double heading_rad,
                                 std::int64_t from_ms, std::int64_t to_ms, AgreementVerdict watch) {
  std::int64_t first = -1;
  for (std::int64_t t = from_ms; t <= to_ms; t += 200) {
    const auto r0 = v.on_message(from(1, 1, raw_imu(heading_rad)), at_ms(t), &mocap);
    const auto r1 = stream(v, mocap, 0.0, 0.0F, t, t, -60'000, watch);
    if (first < 0 && r1 >= 0) first = r1;
    (void)r0;
  }
  return first;
}

TEST(VehicleAgreement, NoseMistakeWithExternalNavYawDisagreesOnTheCompass) {
  // Issue 48: the body was created nose-left, so mocap's yaw is 90° off the vehicle's real
  // heading; EKF3 fuses that yaw and reports it back (yaw offset 0), on the ground the positions
  // coincide, the tilt is level in both. Only the compass (RAW_IMU: east, 90°) tells.
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(external_nav_with_compass(), HostTime{});
  EXPECT_TRUE(v.heading_wanted());
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  EXPECT_EQ(stream_with_heading(v, mocap, kPi / 2, 0, 5'000, AgreementVerdict::disagree), 3'000);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 90.0, 1e-4);
  EXPECT_NEAR(*v.agreement().heading_rad, kPi / 2, 1e-6);
  EXPECT_NEAR(*v.agreement().yaw_offset_deg, 0.0, 1e-4);
  EXPECT_NEAR(*v.agreement().tilt_offset_deg, 0.0, 1e-4);
}

TEST(VehicleAgreement, ACompassWithin45DegreesAgreesAndItsAbsenceKeepsTheVerdictOpen) {
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(external_nav_with_compass(), HostTime{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  // No RAW_IMU yet: the nose is not checked, so no agreement.
  EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, 0, 2'000, -60'000, AgreementVerdict::agree), -1);
  EXPECT_FALSE(v.agreement().heading_offset_deg);
  // A compass 30° off (steel in the floor) still agrees: 45° is the limit.
  EXPECT_EQ(
      stream_with_heading(v, mocap, 30.0 * kPi / 180.0, 2'200, 3'000, AgreementVerdict::agree),
      2'200);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 30.0, 0.2);
  // RAW_IMU stops: older than kHeadingFresh it is not compared, and the agreement lapses.
  (void)stream(v, mocap, 0.0, 0.0F, 3'200, 3'800, -60'000, AgreementVerdict::unknown);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);  // 0.8 s: still fresh
  EXPECT_EQ(stream(v, mocap, 0.0, 0.0F, 4'000, 4'400, -60'000, AgreementVerdict::unknown), 4'200);
  EXPECT_FALSE(v.agreement().heading_offset_deg);
  // With no compass in use the sources say so, and the check agrees without a heading.
  EstimateSources no_compass = external_nav_with_compass();
  no_compass.heading = {EstimateSource::none, "COMPASS_ENABLE = 0: no compass"};
  EXPECT_TRUE(v.set_estimate_sources(no_compass, at_ms(4'500)).agreement_changed);
  EXPECT_FALSE(v.heading_wanted());
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
  EXPECT_EQ(stream_with_heading(v, mocap, kPi, 4'600, 8'000, AgreementVerdict::disagree), -1);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::agree);
  EXPECT_FALSE(v.agreement().heading_offset_deg);  // RAW_IMU arriving, not compared
}

TEST(VehicleAgreement, TheCompassHeadingTakesTheVehiclesDeclination) {
  // A nose 20° east of true north where the declination is 12° east: the compass reads 8°
  // magnetic; COMPASS_DEC (0.2094 rad) makes it 20° true, the 20° mocap says: offset 0.
  VehicleState v(VehicleStateConfig{});
  EstimateSources s = external_nav_with_compass();
  s.declination_rad = 12.0 * kPi / 180.0;
  (void)v.set_estimate_sources(s, HostTime{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 20.0 * kPi / 180.0);
  (void)stream_with_heading(v, mocap, 8.0 * kPi / 180.0, 0, 1'000, AgreementVerdict::agree);
  ASSERT_TRUE(v.agreement().heading_offset_deg);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 0.0, 0.2);
  EXPECT_NEAR(*v.agreement().heading_rad, 20.0 * kPi / 180.0, 0.2 * kPi / 180.0);
}

TEST(VehicleAgreement, ADeclinationReadAfterTheFieldTurnsTheHeadingAlreadyCompared) {
  // RAW_IMU arrives before COMPASS_DEC is read (the set-up list reads it last): the heading
  // compared is magnetic until then; once read, it turns at once, not at the next ATTITUDE.
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(external_nav_with_compass(), HostTime{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 20.0 * kPi / 180.0);
  (void)stream_with_heading(v, mocap, 8.0 * kPi / 180.0, 0, 1'000, AgreementVerdict::agree);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, -12.0, 0.2);
  EstimateSources declined = external_nav_with_compass();
  declined.declination_rad = 12.0 * kPi / 180.0;
  (void)v.set_estimate_sources(declined, at_ms(1'050));
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 0.0, 0.2);
  EXPECT_NEAR(*v.agreement().heading_rad, 20.0 * kPi / 180.0, 0.2 * kPi / 180.0);
}

TEST(VehicleAgreement, AnAllZeroRawImuFieldIsNoCompass) {
  // ArduPilot fills RAW_IMU's field with zeros where it has no compass: no heading, so the nose
  // stays unchecked and nothing agrees on it.
  VehicleState v(VehicleStateConfig{});
  (void)v.set_estimate_sources(external_nav_with_compass(), HostTime{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  for (std::int64_t t = 0; t <= 2'000; t += 200) {
    (void)v.on_message(from(1, 1, mavlink::RawImu{}), at_ms(t), &mocap);
    (void)stream(v, mocap, 0.0, 0.0F, t, t, -60'000, AgreementVerdict::agree);
  }
  EXPECT_FALSE(v.agreement().heading_offset_deg);
  EXPECT_NE(v.agreement().verdict, AgreementVerdict::agree);
}

TEST(MagneticHeading, IsTheLevelledFieldsDirection) {
  // Earth's field 0.2 G north, 0.4 G down. Nose east, level: the body (x east, y south, z down)
  // sees (0, -0.2, 0.4), heading 90°.
  EXPECT_NEAR(magnetic_heading_rad({0.0, -0.2, 0.4}, 0.0, 0.0), kPi / 2, 1e-12);
  // Nose north, rolled 10° right: the body sees (0.2, 0.4 sin 10°, 0.4 cos 10°); read untilted
  // that is -19.2°, levelled it is north.
  const double r = 10.0 * kPi / 180.0;
  EXPECT_NEAR(magnetic_heading_rad({0.2, 0.4 * std::sin(r), 0.4 * std::cos(r)}, r, 0.0), 0.0,
              1e-12);
  EXPECT_TRUE(std::isnan(magnetic_heading_rad({0.0, 0.0, 0.4}, 0.0, 0.0)));
}

TEST(VehicleAgreement, Px4NoseMistakeWithVisionYawDisagreesOnItsMagnetometer) {
  // PX4 with EKF2_EV_CTRL 15 reports mocap's yaw back; its magnetometer (HIGHRES_IMU) says the
  // nose is east while mocap says north.
  VehicleState v(VehicleStateConfig{});
  EstimateSources s{{EstimateSource::mocap, "EKF2_EV_CTRL = 15"},
                    {EstimateSource::mocap, "EKF2_EV_CTRL = 15"}};
  s.heading = {EstimateSource::independent, "the magnetometer in HIGHRES_IMU: SYS_HAS_MAG = 1"};
  (void)v.set_estimate_sources(s, HostTime{});
  const auto mocap = mocap_at({0.0, 0.0, -1.0}, 0.0);
  mavlink::HighresImu imu;
  imu.xmag = 0.0F;
  imu.ymag = -0.2F;
  imu.zmag = 0.4F;
  imu.fields_updated = 0x1FF;  // accel, gyro, mag
  std::int64_t first = -1;
  for (std::int64_t t = 0; t <= 5'000; t += 200) {
    (void)v.on_message(from(1, 1, imu), at_ms(t), &mocap);
    const auto r = stream(v, mocap, 0.0, 0.0F, t, t, -60'000, AgreementVerdict::disagree);
    if (first < 0 && r >= 0) first = r;
  }
  EXPECT_EQ(first, 3'000);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 90.0, 1e-3);
  // A sample without the magnetometer's bits is not a field.
  imu.fields_updated = 0x3F;
  imu.ymag = 0.2F;
  (void)v.on_message(from(1, 1, imu), at_ms(5'100), &mocap);
  (void)stream(v, mocap, 0.0, 0.0F, 5'200, 5'200, -60'000, AgreementVerdict::agree);
  EXPECT_NEAR(*v.agreement().heading_offset_deg, 90.0, 1e-3);
}

TEST(VehicleAgreement, PositionOffsetDisagreesAndLostMocapIsIgnored) {
  VehicleState v(VehicleStateConfig{});
  auto mocap = mocap_at({0.0, 0.0, 0.0}, 0.0);
  v.on_message(from(1, 1, attitude(0.0)), at_ms(0), &mocap);
  v.on_message(from(1, 1, local(0.0F, 0.4F, 0.0F)), at_ms(0), &mocap);
  v.on_message(from(1, 1, local(0.0F, 0.4F, 0.0F)), at_ms(3'000), &mocap);
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.4, 1e-6);
  mocap.state = TrackingState::lost;
  v.on_message(from(1, 1, local(0.0F, 0.0F, 0.0F)), at_ms(3'200), &mocap);  // ignored
  EXPECT_NEAR(*v.agreement().position_offset_m, 0.4, 1e-6);
  v.on_message(from(1, 1, local(0.0F, 0.0F, 0.0F)), at_ms(3'400), nullptr);  // ignored
  EXPECT_EQ(v.agreement().verdict, AgreementVerdict::disagree);
}

}  // namespace
}  // namespace mocaplink::core

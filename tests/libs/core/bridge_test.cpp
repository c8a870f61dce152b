// Bridge: config validation, the step functions end to end with injected time (frames → poses,
// loss → no pose / GPS fix 0, vehicle messages → TIMESYNC replies and origin confirmation, ticks →
// heartbeats), capture-time mapping, runtime control, vehicles added and removed at run time and
// the snapshot.
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/quaternion.hpp"

#include "mocaplink/mavlink/frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using namespace std::chrono_literals;

const GeodeticPosition kOrigin{47.3977418, 8.5455938, 488.0};

VehicleSpec vehicle(std::string name, std::string body, Profile profile, std::uint8_t sysid) {
  VehicleSpec v;
  v.name = std::move(name);
  v.body = std::move(body);
  v.profile = profile;
  v.system_id = sysid;
  return v;
}

BridgeConfig two_vehicles() {
  BridgeConfig c;
  c.world = *WorldAxisMapping::parse("+z", "+x");  // Vicon: NED = (x, −y, −z)
  c.origin = kOrigin;
  c.vehicles.push_back(vehicle("quad", "Quad", Profile::px4, 1));
  c.vehicles.push_back(vehicle("rover", "Rover", Profile::ardupilot_gps, 2));
  c.vehicles[1].rate_hz = 10.0;
  c.timesync_requests = false;
  return c;
}

Bridge make_bridge(const BridgeConfig& c) {
  auto made = Bridge::make(c, HostTime{seconds(100)});
  if (auto* error = std::get_if<BridgeConfigError>(&made)) {
    ADD_FAILURE() << error->field << ": " << error->message;
  }
  return std::get<Bridge>(std::move(made));
}

MocapFrame frame_at(std::uint64_t n, bool quad, bool rover) {
  MocapFrame f;
  f.frame_number = n;
  f.capture_time = SourceTime{milliseconds(10 * static_cast<std::int64_t>(n))};
  f.source_latency = milliseconds(2);
  BodySample q;
  q.name = "Quad";
  q.tracked = quad;
  q.p_world_m = {1.0, 2.0, 3.0};
  f.bodies.push_back(q);
  BodySample r;
  r.name = "Rover";
  r.tracked = rover;
  r.p_world_m = {-1.0, 0.5, 0.0};
  if (rover) f.bodies.push_back(r);  // an untracked rover is simply absent from the frame
  return f;
}

/// Host receive time of frame n: the source clock + 100 s, received 5 ms after capture.
HostTime received_at(std::uint64_t n) {
  return HostTime{seconds(100) + milliseconds(10 * static_cast<std::int64_t>(n) + 5)};
}

template <typename M>
std::vector<std::pair<std::size_t, M>> of_type(const BridgeOutput& out) {
  std::vector<std::pair<std::size_t, M>> v;
  for (const auto& m : out.messages) {
    if (const auto* p = std::get_if<M>(&m.message)) v.emplace_back(m.vehicle, *p);
  }
  return v;
}

TEST(BridgeConfigCheck, RefusesInvalidConfigs) {
  auto expect_error = [](BridgeConfig c, const std::string& field) {
    auto made = Bridge::make(c, HostTime{});
    ASSERT_TRUE(std::holds_alternative<BridgeConfigError>(made)) << field;
    EXPECT_EQ(std::get<BridgeConfigError>(made).field, field);
  };
  BridgeConfig c = two_vehicles();
  c.origin.reset();
  expect_error(c, "origin");  // GPS_INPUT needs one
  c = two_vehicles();
  c.vehicles[1].name = "quad";
  expect_error(c, "vehicle[2].name");
  c = two_vehicles();
  c.vehicles[0].rate_hz = 0.0;
  expect_error(c, "vehicle[1].rate_hz");
  c = two_vehicles();
  c.vehicles[0].component_id = 1;
  expect_error(c, "vehicle[1].component_id");
  c = two_vehicles();
  c.vehicles[0].profile = Profile::custom;
  expect_error(c, "vehicle[1].messages");
  c = two_vehicles();
  c.origin = GeodeticPosition{91.0, 0.0, 0.0};
  expect_error(c, "origin");
  c = two_vehicles();
  c.tracking.gate_sigma = -1.0;
  expect_error(c, "tracking.gate_sigma");
}

TEST(BridgeFrames, ReusedOutputHoldsOnlyTheLatestFrame) {
  // Two bridges fed the same frames: one returns a fresh output, the other refills one object.
  Bridge fresh = make_bridge(two_vehicles());
  Bridge reused = make_bridge(two_vehicles());
  BridgeOutput kept;
  for (std::uint64_t n = 1; n <= 30; ++n) {
    const BridgeOutput expected = fresh.on_frame(frame_at(n, n < 20, true), received_at(n));
    reused.on_frame(frame_at(n, n < 20, true), received_at(n), kept);
    ASSERT_EQ(kept.messages.size(), expected.messages.size()) << n;
    for (std::size_t i = 0; i < kept.messages.size(); ++i) {
      EXPECT_EQ(kept.messages[i].vehicle, expected.messages[i].vehicle);
      EXPECT_EQ(kept.messages[i].message.index(), expected.messages[i].message.index());
    }
    EXPECT_EQ(kept.events.size(), expected.events.size()) << n;
  }
}

TEST(BridgeFrames, PosesInNedWithCaptureTimestamps) {
  Bridge bridge = make_bridge(two_vehicles());
  BridgeOutput last;
  std::size_t odometry = 0;
  for (std::uint64_t n = 1; n <= 100; ++n) {
    last = bridge.on_frame(frame_at(n, true, true), received_at(n));
    odometry += of_type<mavlink::Odometry>(last).size();
    for (const auto& m : last.messages) {
      // Vision messages go to the px4 vehicle only, GPS to the other: per-vehicle unicast.
      if (std::holds_alternative<mavlink::Odometry>(m.message)) {
        EXPECT_EQ(m.vehicle, 0U);
      }
      if (std::holds_alternative<mavlink::GpsInput>(m.message)) {
        EXPECT_EQ(m.vehicle, 1U);
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(odometry), 50.0, 1.0);  // 1 s at 50 Hz
  // The last ODOMETRY: mocap (1, 2, 3) with +z up, +x north → NED (1, −2, −3).
  const auto snapshot = bridge.snapshot(received_at(100));
  const auto& quad = snapshot.bodies[0].estimate;
  EXPECT_NEAR(quad.p_ned_m.x(), 1.0, 1e-6);
  EXPECT_NEAR(quad.p_ned_m.y(), -2.0, 1e-6);
  EXPECT_NEAR(quad.p_ned_m.z(), -3.0, 1e-6);
  // time_usec = receive − reported latency: frame n captured at 100 s + 10n ms + 3 ms.
  BridgeOutput out = bridge.on_frame(frame_at(102, true, true), received_at(102));
  const auto odo = of_type<mavlink::Odometry>(out);
  ASSERT_EQ(odo.size(), 1U);
  EXPECT_EQ(odo[0].second.time_usec, 101'023'000U);
  EXPECT_NEAR(odo[0].second.x, 1.0F, 1e-5F);
  EXPECT_NEAR(odo[0].second.y, -2.0F, 1e-5F);
  EXPECT_NEAR(odo[0].second.z, -3.0F, 1e-5F);
}

TEST(BridgeFrames, AMirroredRotationIsNamedOnceAsNoAxisSettingsMistake) {
  // A source sending a left-handed matrix (wire: BodySample::mirrored): no pose is sent, and the
  // log says why once — not again while it lasts, again after the body was tracked in between.
  Bridge bridge = make_bridge(two_vehicles());
  const auto mirrored_frame = [](std::uint64_t n) {
    MocapFrame f = frame_at(n, false, true);
    f.bodies[0].mirrored = true;
    return f;
  };
  std::vector<BridgeEvent> named;
  std::size_t odometry = 0;
  const auto run = [&](std::uint64_t from, std::uint64_t to, bool mirrored) {
    for (std::uint64_t n = from; n <= to; ++n) {
      const BridgeOutput out =
          bridge.on_frame(mirrored ? mirrored_frame(n) : frame_at(n, true, true), received_at(n));
      for (const auto& [v, m] : of_type<mavlink::Odometry>(out)) odometry += v == 0 ? 1 : 0;
      for (const BridgeEvent& e : out.events) {
        if (e.kind == BridgeEventKind::body_mirrored) named.push_back(e);
      }
    }
  };
  run(1, 200, true);
  EXPECT_EQ(odometry, 0U);
  ASSERT_EQ(named.size(), 1U);
  EXPECT_EQ(named[0].subject, "Quad");
  EXPECT_EQ(named[0].text,
            "the source's rotation is mirrored (a left-handed matrix, determinant -1): not a pose, "
            "so none is sent; no up, north, body_forward or body_up setting can fix it: check "
            "the handedness of the mocap system's or its streaming tool's frame");
  EXPECT_EQ(to_string(BridgeEventKind::body_mirrored), "body_mirrored");
  run(201, 300, false);  // the right frame: tracked, poses sent
  EXPECT_GT(odometry, 0U);
  run(301, 310, true);  // mirrored again: named again
  EXPECT_EQ(named.size(), 2U);
}

TEST(BridgeFrames, LostBodyStopsPosesAndGpsReportsNoFix) {
  BridgeConfig c = two_vehicles();
  c.vehicles[0].profile = Profile::custom;  // ODOMETRY + GPS_INPUT on the same body
  c.vehicles[0].messages = {MessageKind::odometry, MessageKind::gps_input};
  Bridge bridge = make_bridge(c);
  BridgeOutput out;
  for (std::uint64_t n = 1; n <= 50; ++n) bridge.on_frame(frame_at(n, true, true), received_at(n));
  std::vector<BridgeEvent> events;
  std::size_t odometry = 0;
  std::vector<std::uint8_t> fixes;
  for (std::uint64_t n = 51; n <= 150; ++n) {  // 1 s occluded
    out = bridge.on_frame(frame_at(n, false, true), received_at(n));
    odometry += of_type<mavlink::Odometry>(out).size();
    for (const auto& [v, g] : of_type<mavlink::GpsInput>(out)) {
      if (v == 0) fixes.push_back(g.fix_type);
    }
    events.insert(events.end(), out.events.begin(), out.events.end());
  }
  EXPECT_EQ(odometry, 0U);  // no stale pose, not even while merely occluded
  ASSERT_FALSE(fixes.empty());
  EXPECT_EQ(fixes.front(), 3);  // still TRACKING for loss_timeout_ms (prediction)
  EXPECT_EQ(fixes.back(), 0);   // then LOST: fix 0, GPS keeps being sent
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].kind, BridgeEventKind::body_lost);
  EXPECT_EQ(events[0].subject, "Quad");
  // Re-acquired in place after 1 s: tracking again; a gap is no jump, reset_counter unchanged.
  events.clear();
  for (std::uint64_t n = 151; n <= 160; ++n) {
    out = bridge.on_frame(frame_at(n, true, true), received_at(n));
    events.insert(events.end(), out.events.begin(), out.events.end());
    odometry += of_type<mavlink::Odometry>(out).size();
  }
  EXPECT_GE(odometry, 1U);
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].kind, BridgeEventKind::body_tracking);
  EXPECT_EQ(bridge.snapshot(received_at(160)).bodies[0].estimate.reset_counter, 0);
}

TEST(BridgeFrames, SourceRestartKeepsPosesFlowingAndResetsOnlyMovedBodies) {
  Bridge bridge = make_bridge(two_vehicles());
  for (std::uint64_t n = 1; n <= 50; ++n) bridge.on_frame(frame_at(n, true, true), received_at(n));
  EXPECT_EQ(bridge.snapshot(received_at(50)).bodies[0].estimate.reset_counter, 0);
  // A reordered datagram (20 ms late) is not a restart: refused by the trackers, nothing sent.
  EXPECT_TRUE(bridge.on_frame(frame_at(48, true, true), received_at(50)).messages.empty());
  EXPECT_EQ(bridge.snapshot(received_at(50)).source_restarts, 0U);
  // The mocap server restarts: its clock (and frame numbers) start again from frame 1, 2 s later,
  // the bodies where they were.
  std::size_t odometry = 0;
  std::uint8_t reset_counter = 0;
  for (std::uint64_t n = 1; n <= 50; ++n) {
    const BridgeOutput out = bridge.on_frame(frame_at(n, true, true), received_at(n) + seconds(2));
    for (const auto& [v, o] : of_type<mavlink::Odometry>(out)) {
      ++odometry;
      reset_counter = o.reset_counter;
    }
    EXPECT_TRUE(std::none_of(out.events.begin(), out.events.end(), [](const BridgeEvent& e) {
      return e.kind == BridgeEventKind::body_reset;
    }));
  }
  EXPECT_NEAR(static_cast<double>(odometry), 25.0, 1.0);  // not refused as "time going back"
  EXPECT_EQ(reset_counter, 0);                            // a restart alone is no jump
  auto s = bridge.snapshot(received_at(50) + seconds(2));
  EXPECT_EQ(s.source_restarts, 1U);
  EXPECT_EQ(s.bodies[0].estimate.counters.resumed, 1U);
  EXPECT_EQ(s.bodies[1].estimate.reset_counter, 0);
  // Restarted again 0.3 s later, and the rover's rigid body was re-defined 1 m off meanwhile: the
  // rover's pose jumped (one increment, one event), the quad's did not.
  std::size_t resets = 0;
  for (std::uint64_t n = 1; n <= 50; ++n) {
    MocapFrame f = frame_at(n, true, true);
    f.bodies[1].p_world_m.x() += 1.0;
    const BridgeOutput out = bridge.on_frame(f, received_at(n) + milliseconds(2800));
    for (const auto& e : out.events) resets += e.kind == BridgeEventKind::body_reset ? 1 : 0;
  }
  s = bridge.snapshot(received_at(50) + seconds(3));
  EXPECT_EQ(s.source_restarts, 2U);
  EXPECT_EQ(resets, 1U);
  EXPECT_EQ(s.bodies[0].name, "Quad");
  EXPECT_EQ(s.bodies[0].estimate.reset_counter, 0);
  EXPECT_EQ(s.bodies[1].estimate.reset_counter, 1);
}

TEST(BridgeFrames, SourceRestartOnAClockAheadIsNoJump) {
  // Issue 49's harness: a Vicon server restarted with its frame numbers from a new base, its
  // clock 1600 s ahead, after 1.05 s away. The quad drifts at 1 cm/s: a gap of 1600 s would put
  // the body 16 m from where it could have got to (a jump); the host's 1.05 s does not.
  Bridge bridge = make_bridge(two_vehicles());
  const auto drifting = [](std::uint64_t n, double t_s) {
    MocapFrame f = frame_at(n, true, true);
    f.bodies[0].p_world_m.x() += 0.01 * t_s;
    return f;
  };
  for (std::uint64_t n = 1; n <= 100; ++n) {
    bridge.on_frame(drifting(n, 0.01 * static_cast<double>(n)), received_at(n));
  }
  std::size_t odometry = 0;
  std::size_t resets = 0;
  for (std::uint64_t k = 1; k <= 50; ++k) {
    const double t_s = 1.0 + 1.05 + 0.01 * static_cast<double>(k);
    const BridgeOutput out = bridge.on_frame(drifting(160000 + k, t_s), received_at(100 + 105 + k));
    odometry += of_type<mavlink::Odometry>(out).size();
    for (const auto& e : out.events) resets += e.kind == BridgeEventKind::body_reset ? 1 : 0;
  }
  auto s = bridge.snapshot(received_at(155 + 100));
  EXPECT_EQ(s.source_restarts, 1U);
  EXPECT_EQ(resets, 0U);
  EXPECT_EQ(s.bodies[0].estimate.reset_counter, 0);
  EXPECT_EQ(s.bodies[0].estimate.counters.resumed, 1U);
  EXPECT_GE(odometry, 20U);
  // A clock that kept running through a 3 s outage (capture and host 3 s on) is no restart: the
  // gap is real, and the quad, 3 cm on, is back where it could have got to.
  for (std::uint64_t k = 1; k <= 50; ++k) {
    const double t_s = 2.55 + 3.0 + 0.01 * static_cast<double>(k);
    bridge.on_frame(drifting(160350 + k, t_s), received_at(455 + k));
  }
  s = bridge.snapshot(received_at(505));
  EXPECT_EQ(s.source_restarts, 1U);
  EXPECT_EQ(s.bodies[0].estimate.reset_counter, 0);
  EXPECT_EQ(s.bodies[0].estimate.counters.resumed, 2U);
}

TEST(SourceClock, ARestartIsAStepBackOrALeapAheadOfTheHost) {
  const SourceTime c{seconds(10)};
  const HostTime r{seconds(100)};
  const Duration back = milliseconds(250);
  EXPECT_FALSE(source_clock_restarted(c, r, c + milliseconds(10), r + milliseconds(10), back));
  EXPECT_FALSE(source_clock_restarted(c, r, c - milliseconds(20), r, back));  // reordered
  EXPECT_TRUE(source_clock_restarted(c, r, c - milliseconds(251), r, back));
  // An outage the clock ran through: 3 s on both clocks, or a burst after a stall.
  EXPECT_FALSE(source_clock_restarted(c, r, c + seconds(3), r + seconds(3), back));
  EXPECT_FALSE(source_clock_restarted(c, r, c + milliseconds(10), r + seconds(3), back));
  // Ahead of the host by more than kSourceClockLeap: a new clock.
  EXPECT_FALSE(source_clock_restarted(c, r, c + seconds(2), r + milliseconds(1001), back));
  EXPECT_TRUE(source_clock_restarted(c, r, c + seconds(2), r + milliseconds(999), back));
  EXPECT_TRUE(source_clock_restarted(c, r, c + seconds(1600), r + milliseconds(1050), back));
}

// Issue 27: a frame's age is judged from its capture, so a frame that continues the stream but
// arrives late (a TCP backlog after a stall, a VRPN round held back, a replay behind schedule) is
// as old as its capture however recently it arrived; a source restart is judged by arrival.
TEST(BridgeFrames, FrameAgeCountsFromTheCaptureOfALateFrame) {
  Bridge bridge = make_bridge(two_vehicles());
  // Nothing to place the first frame by: its age is the time since it was received.
  EXPECT_EQ(bridge.frame_age(frame_at(1, true, true), received_at(1), received_at(1) + 3ms),
            milliseconds(3));
  for (std::uint64_t n = 1; n <= 50; ++n) bridge.on_frame(frame_at(n, true, true), received_at(n));
  // On time: the source reports 2 ms of its own latency, and the least-delayed frames set the
  // clocks' offset (their transport counts as none): 2 ms old when received, 3 ms 1 ms later.
  EXPECT_EQ(bridge.frame_age(frame_at(51, true, true), received_at(51), received_at(51)),
            milliseconds(2));
  EXPECT_EQ(bridge.frame_age(frame_at(51, true, true), received_at(51), received_at(51) + 1ms),
            milliseconds(3));
  // The stream stalls for 600 ms and then frames 51.. arrive in a burst: received just now, but
  // captured 600 ms before. The first is that old, a later one of the burst less so.
  const HostTime burst = received_at(51) + 600ms;
  EXPECT_EQ(bridge.frame_age(frame_at(51, true, true), burst, burst), milliseconds(602));
  EXPECT_EQ(bridge.frame_age(frame_at(100, true, true), burst, burst), milliseconds(112));
  // Waiting in the queue still counts when the capture says less (a frame received long ago).
  EXPECT_EQ(bridge.frame_age(frame_at(51, true, true), received_at(51), received_at(51) + 400ms),
            milliseconds(402));
  // The source restarts (its clock starts again from frame 1): judged by arrival, not as 0.5 s old.
  EXPECT_EQ(bridge.frame_age(frame_at(1, true, true), burst, burst + 2ms), milliseconds(2));
  // A source clock that jumped forward (captured "after" now): by arrival, never negative.
  EXPECT_EQ(bridge.frame_age(frame_at(5000, true, true), burst, burst + 2ms), milliseconds(2));
  // Asking changes nothing: the next frame on time is still 2 ms old.
  EXPECT_EQ(bridge.frame_age(frame_at(52, true, true), received_at(52), received_at(52)),
            milliseconds(2));
}

TEST(BridgeVehicles, TimesyncReplyOriginAndHeartbeats) {
  Bridge bridge = make_bridge(two_vehicles());
  // Before the vehicle is heard: heartbeats, no origin (origin_gate).
  BridgeOutput out = bridge.on_tick(HostTime{seconds(99)});
  EXPECT_EQ(of_type<mavlink::Heartbeat>(out).size(), 2U);
  EXPECT_TRUE(of_type<mavlink::SetGpsGlobalOrigin>(out).empty());
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotArdupilot;
  bridge.on_vehicle_message(0, {1, 1, hb}, HostTime{seconds(99) + milliseconds(500)});
  // Tick at 100 s: vehicle 0's heartbeat, and SET_GPS_GLOBAL_ORIGIN only for the vision vehicle;
  // vehicle 1's heartbeat keeps a phase of its own (0.618 s: Sender::on_tick), due at 100.618 s.
  out = bridge.on_tick(HostTime{seconds(100)});
  ASSERT_EQ(of_type<mavlink::Heartbeat>(out).size(), 1U);
  EXPECT_EQ(of_type<mavlink::Heartbeat>(out)[0].first, 0U);
  auto origins = of_type<mavlink::SetGpsGlobalOrigin>(out);
  ASSERT_EQ(origins.size(), 1U);
  EXPECT_EQ(origins[0].first, 0U);
  EXPECT_EQ(origins[0].second.target_system, 1);
  for (const auto& m : out.messages) {
    EXPECT_EQ(m.frame.bytes()[5], m.vehicle == 0 ? 1 : 2);  // source sysid = the vehicle's
    EXPECT_EQ(m.frame.bytes()[6], 197);
  }
  // TIMESYNC request from the px4 autopilot: answered at once with our clock.
  mavlink::Timesync request;
  request.ts1 = 555;
  out = bridge.on_vehicle_message(0, {1, 1, request}, HostTime{seconds(100) + milliseconds(250)});
  auto replies = of_type<mavlink::Timesync>(out);
  ASSERT_EQ(replies.size(), 1U);
  EXPECT_EQ(replies[0].second.tc1, 100'250'000'000);
  EXPECT_EQ(replies[0].second.ts1, 555);
  EXPECT_EQ(replies[0].second.target_system, 1);
  EXPECT_EQ(replies[0].second.target_component, 1);
  // Matching GPS_GLOBAL_ORIGIN: confirmed, and no SET_GPS_GLOBAL_ORIGIN any more.
  mavlink::GpsGlobalOrigin reported;
  reported.latitude = 473977418;
  reported.longitude = 85455938;
  reported.altitude = 488000;
  out = bridge.on_vehicle_message(0, {1, 1, reported}, HostTime{seconds(100) + milliseconds(500)});
  ASSERT_EQ(out.events.size(), 1U);
  EXPECT_EQ(out.events[0].kind, BridgeEventKind::origin_state);
  EXPECT_EQ(out.events[0].text, "origin confirmed");
  out = bridge.on_tick(HostTime{seconds(101)});
  EXPECT_EQ(of_type<mavlink::Heartbeat>(out).size(), 2U);
  EXPECT_TRUE(of_type<mavlink::SetGpsGlobalOrigin>(out).empty());
  EXPECT_EQ(bridge.snapshot(HostTime{seconds(101)}).vehicles[0].vehicle.origin,
            OriginState::confirmed);
  // Out-of-range vehicle index: ignored.
  EXPECT_TRUE(bridge.on_vehicle_message(9, {1, 1, request}, HostTime{}).messages.empty());
}

TEST(BridgeVehicles, ARebootedVehicleIsSentTheOriginAgain) {
  // Seen against ArduCopter SITL: after the set-up's reboot the origin stayed "confirmed", none
  // was sent, and the vehicle never armed ("PreArm: AHRS: waiting for home").
  Bridge bridge = make_bridge(two_vehicles());
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotArdupilot;
  const HostTime t0{seconds(100)};
  bridge.on_vehicle_message(0, {1, 1, hb}, t0);
  mavlink::GpsGlobalOrigin reported;
  reported.latitude = 473977418;
  reported.longitude = 85455938;
  reported.altitude = 488000;
  bridge.on_vehicle_message(0, {1, 1, reported}, t0);
  mavlink::Attitude att;
  att.time_boot_ms = 60'000;
  bridge.on_vehicle_message(0, {1, 1, att}, t0);
  EXPECT_TRUE(of_type<mavlink::SetGpsGlobalOrigin>(bridge.on_tick(t0)).empty());
  // The boot clock goes back: a reboot. The next tick says so; the one after sends the origin.
  att.time_boot_ms = 900;
  bridge.on_vehicle_message(0, {1, 1, hb}, t0 + seconds(1));
  bridge.on_vehicle_message(0, {1, 1, att}, t0 + seconds(1));
  const BridgeOutput seen = bridge.on_tick(t0 + seconds(1));
  const auto event = std::find_if(seen.events.begin(), seen.events.end(), [](const BridgeEvent& e) {
    return e.kind == BridgeEventKind::origin_state;
  });
  ASSERT_NE(event, seen.events.end());
  EXPECT_EQ(event->text, "origin sending: the vehicle rebooted and lost the origin it had");
  EXPECT_EQ(bridge.snapshot(t0 + seconds(1)).vehicles[0].vehicle.origin, OriginState::sending);
  const auto origins = of_type<mavlink::SetGpsGlobalOrigin>(bridge.on_tick(t0 + seconds(2)));
  ASSERT_EQ(origins.size(), 1U);
  EXPECT_EQ(origins[0].first, 0U);
  EXPECT_EQ(origins[0].second.latitude, 473977418);
}

/// Ticks `bridge` 100 ms apart from `from` for `count` ticks, vehicle 0's PX4 heartbeat every
/// 0.5 s, and its AUTOPILOT_VERSION (`version`, 0 = never) answered at the first request; returns
/// the SET_GPS_GLOBAL_ORIGIN sent and the origin events.
std::pair<std::size_t, std::vector<std::string>> px4_origin_run(Bridge& bridge, HostTime from,
                                                                int count, std::uint32_t version) {
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotPx4;
  std::size_t origins = 0;
  std::vector<std::string> events;
  for (int k = 0; k < count; ++k) {
    const HostTime now = from + milliseconds(100 * k);
    if (k % 5 == 0) bridge.on_vehicle_message(0, {1, 1, hb}, now);
    const BridgeOutput out = bridge.on_tick(now);
    origins += of_type<mavlink::SetGpsGlobalOrigin>(out).size();
    for (const BridgeEvent& e : out.events) {
      if (e.kind == BridgeEventKind::origin_state && e.vehicle == 0) events.push_back(e.text);
    }
    for (const auto& c : of_type<mavlink::CommandLong>(out)) {
      if (c.first == 0 && c.second.command == 512 && version != 0) {  // REQUEST_MESSAGE
        mavlink::AutopilotVersion v;
        v.flight_sw_version = version;
        bridge.on_vehicle_message(0, {1, 1, v}, now + milliseconds(20));
      }
    }
  }
  return {origins, events};
}

TEST(BridgeVehicles, Px4Before115IsNeverSentTheOrigin) {
  // PX4 1.14.3 SITL without GPS took mocaplink's origin 1.2 s after boot, shifted its height
  // estimate by the origin's altitude (32.34 m) and a 1 m Offboard hover climbed to 18.65 m.
  const HostTime t0{seconds(100)};
  {
    Bridge bridge = make_bridge(two_vehicles());
    const auto [origins, events] =
        px4_origin_run(bridge, t0, 100, (1U << 24) | (14U << 16) | (3U << 8) | 255U);
    EXPECT_EQ(origins, 0U);
    ASSERT_EQ(events.size(), 1U);
    EXPECT_EQ(events[0].rfind("origin withheld: PX4 1.14.3 is not sent the origin: before 1.15", 0),
              0U)
        << events[0];
    EXPECT_EQ(bridge.snapshot(t0 + seconds(10)).vehicles[0].vehicle.origin, OriginState::withheld);
    // It reboots: nothing was sent, so nothing was "lost"; the version decides again.
    mavlink::Attitude att;
    att.time_boot_ms = 60'000;
    bridge.on_vehicle_message(0, {1, 1, att}, t0 + seconds(10));
    att.time_boot_ms = 900;
    bridge.on_vehicle_message(0, {1, 1, att}, t0 + seconds(11));
    const auto [again, after] =
        px4_origin_run(bridge, t0 + seconds(11), 60, (1U << 24) | (14U << 16) | (3U << 8) | 255U);
    EXPECT_EQ(again, 0U);
    for (const std::string& e : after) EXPECT_EQ(e.find("lost the origin"), std::string::npos) << e;
    EXPECT_EQ(bridge.snapshot(t0 + seconds(17)).vehicles[0].vehicle.origin, OriginState::withheld);
  }
  {  // One that never says its version: the same, once it has been asked 3 times.
    Bridge bridge = make_bridge(two_vehicles());
    const auto [origins, events] = px4_origin_run(bridge, t0, 100, 0);
    EXPECT_EQ(origins, 0U);
    ASSERT_EQ(events.size(), 1U);
    EXPECT_NE(events[0].find("PX4 of unknown version is not sent the origin"), std::string::npos);
  }
  {  // 1.15: sent, about once a second from the version's answer.
    Bridge bridge = make_bridge(two_vehicles());
    const auto [origins, events] = px4_origin_run(bridge, t0, 100, (1U << 24) | (15U << 16) | 255U);
    EXPECT_GE(origins, 9U);
    EXPECT_TRUE(events.empty());
    EXPECT_EQ(bridge.snapshot(t0 + seconds(10)).vehicles[0].vehicle.origin, OriginState::sending);
  }
}

TEST(BridgeVehicles, HeartbeatStateAndAgreementEvents) {
  Bridge bridge = make_bridge(two_vehicles());
  for (std::uint64_t n = 1; n <= 20; ++n) bridge.on_frame(frame_at(n, true, true), received_at(n));
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = 12;
  BridgeOutput out = bridge.on_vehicle_message(0, {1, 1, hb}, received_at(20));
  ASSERT_EQ(out.events.size(), 1U);
  EXPECT_EQ(out.events[0].text, "link alive");
  // The vehicle reports its own estimate: right place, nose 90° off (body not nose-forward).
  mavlink::LocalPositionNed pos;
  pos.x = 1.0F;
  pos.y = -2.0F;
  pos.z = -3.0F;
  mavlink::Attitude att;
  att.yaw = static_cast<float>(std::numbers::pi / 2);
  pos.time_boot_ms = 60'000;  // a vehicle up for a minute: past kAgreementSettle
  att.time_boot_ms = 60'000;
  bridge.on_vehicle_message(0, {1, 1, pos}, received_at(20));
  out = bridge.on_vehicle_message(0, {1, 1, att}, received_at(20));
  EXPECT_TRUE(out.events.empty());  // disagreeing, not yet for kAgreementHold
  for (std::uint64_t n = 21; n <= 320; ++n)
    bridge.on_frame(frame_at(n, true, true), received_at(n));
  att.time_boot_ms += 3'000;
  out = bridge.on_vehicle_message(0, {1, 1, att}, received_at(320));  // 3 s later: the verdict
  ASSERT_EQ(out.events.size(), 1U);
  EXPECT_EQ(out.events[0].kind, BridgeEventKind::agreement);
  const auto agreement = bridge.snapshot(received_at(320)).vehicles[0].vehicle.agreement;
  EXPECT_EQ(agreement.verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*agreement.yaw_offset_deg, 90.0, 0.5);
  EXPECT_NEAR(*agreement.position_offset_m, 0.0, 1e-3);
  out = bridge.on_tick(received_at(20) + seconds(4));
  ASSERT_FALSE(out.events.empty());
  EXPECT_EQ(out.events[0].text, "link silent");
}

/// Issue 48: a Z-up Vicon (the Quad level, nose on mocap +x: identity quaternions) configured with
/// `up` as given, bridged to an ArduCopter whose EKF3 takes yaw and position from ExternalNav
/// (EK3_SRC1_YAW = 6, EK3_SRC1_POSXY = 6, every other parameter 0) and that reports, level on
/// its IMU, the yaw and position mocaplink sends it. Returns the agreement after 12 s and the
/// agreement events' texts.
/// Vehicle 0 reports mocaplink's own pose of body 0 back as its estimate (ATTITUDE yaw and
/// LOCAL_POSITION_NED stamped `boot`), as a vehicle fusing our poses does; `keep` sees each output.
template <typename Keep>
void echo_estimate(Bridge& bridge, HostTime now, std::uint32_t boot, const Keep& keep,
                   double yaw_offset_rad = 0.0) {
  const BodyEstimate sent = bridge.snapshot(now).bodies[0].estimate;  // a copy: the snapshot goes
  mavlink::Attitude att;
  att.time_boot_ms = boot;
  att.yaw = static_cast<float>(euler_321_from_quaternion(sent.q_ned_frd).yaw_rad + yaw_offset_rad);
  mavlink::LocalPositionNed pos;
  pos.time_boot_ms = boot;
  pos.x = static_cast<float>(sent.p_ned_m.x());
  pos.y = static_cast<float>(sent.p_ned_m.y());
  pos.z = static_cast<float>(sent.p_ned_m.z());
  keep(bridge.on_vehicle_message(0, {1, 1, att}, now));
  keep(bridge.on_vehicle_message(0, {1, 1, pos}, now));
}

/// `ek3_yaw`: EK3_SRC1_YAW (6 ExternalNav: its yaw is mocap's; 1 compass: its own), and its yaw
/// reported `yaw_offset_rad` off the pose it was sent.
std::pair<Agreement, std::vector<std::string>> external_nav_quad(std::string_view up,
                                                                 float ek3_yaw = 6.0F,
                                                                 double yaw_offset_rad = 0.0) {
  BridgeConfig c = two_vehicles();
  c.world = *WorldAxisMapping::parse(up, "+x");
  c.source_up = axis::pos_z;
  c.vehicles = {vehicle("quad", "Quad", Profile::ardupilot, 1)};
  Bridge bridge = make_bridge(c);
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotArdupilot;
  std::vector<std::string> events;
  const auto keep = [&](const BridgeOutput& out) {
    for (const BridgeEvent& e : out.events) {
      if (e.kind == BridgeEventKind::agreement) events.push_back(e.text);
    }
  };
  for (std::uint64_t n = 1; n <= 1200; ++n) {  // 12 s of 100 Hz frames
    const HostTime now = received_at(n);
    bridge.on_frame(frame_at(n, true, false), now);
    if (n % 10 != 0) continue;
    if (n % 50 == 0) keep(bridge.on_vehicle_message(0, {1, 1, hb}, now));
    const BridgeOutput ticked = bridge.on_tick(now);
    keep(ticked);
    for (const auto& m : ticked.messages) {
      if (const auto* r = std::get_if<mavlink::ParamRequestRead>(&m.message)) {
        const std::string name(r->param_id.begin(),
                               std::find(r->param_id.begin(), r->param_id.end(), '\0'));
        mavlink::ParamValue v;
        v.param_id = r->param_id;
        v.param_type = 2;  // INT8, the value cast to float (ArduPilot)
        // Every other parameter 0: COMPASS_ENABLE too, so there is no heading of its own.
        v.param_value = name == "EK3_SRC1_YAW" ? ek3_yaw : name == "EK3_SRC1_POSXY" ? 6.0F : 0.0F;
        keep(bridge.on_vehicle_message(0, {1, 1, v}, now));
      }
    }
    if (n % 20 != 0) continue;  // its estimate at 5 Hz: mocaplink's own pose, fed back
    echo_estimate(bridge, now, static_cast<std::uint32_t>(60'000 + 10 * n), keep, yaw_offset_rad);
  }
  return {bridge.snapshot(received_at(1200)).vehicles[0].vehicle.agreement, events};
}

TEST(BridgeVehicles, AxesThatFitBesideADisagreementPointAtTheVehiclesEstimate) {
  // Its own (compass) yaw 20° off mocap's: the yaw check (10°) disagrees, but the axes fit at
  // rest (the fix search allows a compass 45°): the fix says it is the vehicle's estimate.
  const auto [agreement, events] = external_nav_quad("+z", 1.0F, 20.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(agreement.verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*agreement.yaw_offset_deg, 20.0, 0.1);
  ASSERT_TRUE(agreement.fix);
  EXPECT_EQ(agreement.fix->kind, AxisFixKind::agrees);
  EXPECT_EQ(agreement.fix->text,
            "no axis change needed: the settings fit the vehicle at rest (tilt 0.0°, heading "
            "20.0°); what disagrees is the vehicle's own estimate, not the axes: its yaw is 20.0° "
            "from mocap's (10° allowed) (a compass that is off, an estimator still converging, "
            "an origin elsewhere)");
}

TEST(BridgeVehicles, AnUpAxisMistakeWithExternalNavYawDisagreesAndNamesTheFix) {
  const auto [agreement, events] = external_nav_quad("+y");
  EXPECT_EQ(agreement.verdict, AgreementVerdict::disagree);
  EXPECT_NEAR(*agreement.tilt_offset_deg, 90.0, 0.1);
  EXPECT_NEAR(*agreement.yaw_offset_deg, 0.0, 0.1);  // mocap's own yaw: no sign of the mistake
  ASSERT_TRUE(agreement.fix);
  EXPECT_EQ(agreement.fix->lines, (std::vector<std::string>{"[mocap] up = \"+z\""}));
  ASSERT_FALSE(events.empty());
  const std::string& last = events.back();
  EXPECT_EQ(last.rfind("estimate disagrees, tilt offset 90.", 0), 0U) << last;
  const std::string tail =
      "; fix: [mocap] up = \"+z\" (then tilt 0.0°, nose unchecked: the vehicle has no heading of "
      "its own); or, as well at this pose: [[vehicle]] body_up = \"+y\"; yaw not checkable: the "
      "vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6), and it has no heading of its own "
      "(COMPASS_ENABLE = 0: no compass): the nose is unchecked; position not checkable: the "
      "vehicle's position comes from mocap (EK3_SRC1_POSXY = 6)";
  ASSERT_GE(last.size(), tail.size());
  EXPECT_EQ(last.substr(last.size() - tail.size()), tail) << last;
}

TEST(BridgeVehicles, TheRightAxesWithExternalNavAgreeOnGravityAlone) {
  const auto [agreement, events] = external_nav_quad("+z");
  EXPECT_EQ(agreement.verdict, AgreementVerdict::agree);
  EXPECT_NEAR(*agreement.tilt_offset_deg, 0.0, 0.1);
  EXPECT_FALSE(agreement.fix);
  ASSERT_FALSE(events.empty());
  const std::string tail =
      "; yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6), and it has no "
      "heading of its own (COMPASS_ENABLE = 0: no compass): the nose is unchecked; position not "
      "checkable: the vehicle's position comes from mocap "
      "(EK3_SRC1_POSXY = 6)";
  const std::string& last = events.back();
  EXPECT_EQ(last.rfind("estimate agrees, tilt offset 0.", 0), 0U) << last;
  ASSERT_GE(last.size(), tail.size());
  EXPECT_EQ(last.substr(last.size() - tail.size()), tail) << last;
}

// A PX4 over uXRCE-DDS (issue 47): its link carries the poses and nothing else, so the Bridge
// sends it no HEARTBEAT, TIMESYNC, origin, stream or parameter request; the set-up list is
// unavailable, and its estimate (as the link turns vehicle_odometry into ATTITUDE and
// LOCAL_POSITION_NED, stamped from when it was first heard) agrees on gravity, yaw and position
// assumed to be mocap's own.
TEST(BridgeVehicles, APx4OverDdsIsSentOnlyPosesAndAgreesOnGravity) {
  BridgeConfig c = two_vehicles();
  c.timesync_requests = true;
  c.vehicles = {vehicle("quad", "Quad", Profile::px4, 1)};
  c.vehicles[0].link = VehicleLink::px4_dds;
  Bridge bridge = make_bridge(c);
  EXPECT_TRUE(bridge.set_capture_stamps(0, true));  // its link judged PX4's time sync right
  mavlink::Heartbeat hb;                            // what px4_link.cpp makes of vehicle_status
  hb.autopilot = kMavAutopilotPx4;
  hb.base_mode = kMavModeFlagSafetyArmed;
  std::size_t odometry = 0;
  std::vector<std::string> setup_events;
  const auto keep = [&](const BridgeOutput& out) {
    for (const auto& m : out.messages) {
      if (std::holds_alternative<mavlink::Odometry>(m.message)) {
        ++odometry;
      } else {
        ADD_FAILURE() << "sent " << mavlink::message_info(m.message).name << " over DDS";
      }
    }
    for (const BridgeEvent& e : out.events) {
      if (e.kind == BridgeEventKind::vehicle_setup) setup_events.push_back(e.text);
    }
  };
  for (std::uint64_t n = 1; n <= 2000; ++n) {  // 20 s of 100 Hz frames
    const HostTime now = received_at(n);
    keep(bridge.on_frame(frame_at(n, true, false), now));
    if (n % 10 != 0) continue;
    if (n % 50 == 0) keep(bridge.on_vehicle_message(0, {1, 1, hb}, now));
    keep(bridge.on_tick(now));
    if (n % 20 != 0) continue;
    echo_estimate(bridge, now, static_cast<std::uint32_t>(10 * n), keep);  // heard from the start
  }
  EXPECT_GT(odometry, 900U);  // 50 Hz
  const VehicleStatus status = bridge.snapshot(received_at(2000)).vehicles[0];
  EXPECT_EQ(status.link, VehicleLink::px4_dds);
  EXPECT_EQ(status.setup.state, SetupState::unavailable);
  EXPECT_EQ(status.sender.counters.heartbeats, 0U);
  EXPECT_EQ(status.sender.counters.timesync_requests, 0U);
  EXPECT_EQ(status.setup.delay.recommended_ms, 0.0);
  ASSERT_EQ(setup_events.size(), 1U);
  EXPECT_EQ(setup_events[0].rfind("set-up unavailable: PX4's parameters do not go over", 0), 0U)
      << setup_events[0];
  const Agreement& agreement = status.vehicle.agreement;
  EXPECT_EQ(agreement.verdict, AgreementVerdict::agree);
  EXPECT_EQ(agreement.sources, px4_dds_sources());
  const auto unchecked = describe_unchecked(agreement.sources);
  ASSERT_TRUE(unchecked);
  EXPECT_EQ(unchecked->rfind("yaw not checkable: the vehicle's yaw comes from mocap (assumed: ", 0),
            0U)
      << *unchecked;
}

TEST(BridgeVehicles, ReadsTheSetUpAsTheVehicleAndAppliesOnlyOnRequest) {
  // Issue 28: AUTOPILOT_VERSION and the profile's parameters are asked for through on_tick, with
  // the vehicle's identity; answers come through on_vehicle_message; the list is in the snapshot;
  // apply_setup writes only what was named.
  Bridge bridge = make_bridge(two_vehicles());
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotArdupilot;
  const HostTime t0{seconds(100)};
  std::vector<std::string> reads;
  std::size_t writes = 0;
  const auto tick = [&](HostTime now) {
    const BridgeOutput out = bridge.on_tick(now);
    for (const auto& m : out.messages) {
      if (const auto* r = std::get_if<mavlink::ParamRequestRead>(&m.message)) {
        EXPECT_EQ(m.vehicle, 0U);
        EXPECT_EQ(m.frame.bytes()[5], 1);    // from the vehicle's own sysid
        EXPECT_EQ(m.frame.bytes()[6], 197);  // and our component
        EXPECT_EQ(r->target_system, 1);
        reads.emplace_back(r->param_id.begin(),
                           std::find(r->param_id.begin(), r->param_id.end(), '\0'));
        // The vehicle answers every read with 0 (ArduPilot: the value cast to float).
        mavlink::ParamValue v;
        v.param_id = r->param_id;
        v.param_type = 2;  // INT8
        bridge.on_vehicle_message(0, {1, 1, v}, now);
      }
      if (std::holds_alternative<mavlink::ParamSet>(m.message)) ++writes;
    }
  };
  for (int k = 0; k <= 80; ++k) {
    const HostTime now = t0 + milliseconds(100 * k);
    if (k % 5 == 0) bridge.on_vehicle_message(0, {1, 1, hb}, now);
    tick(now);
  }
  EXPECT_FALSE(reads.empty());
  EXPECT_NE(std::find(reads.begin(), reads.end(), "VISO_TYPE"), reads.end());
  const BridgeSnapshot snap = bridge.snapshot(t0 + seconds(8));
  const VehicleSetupSnapshot& setup = snap.vehicles[0].setup;
  EXPECT_EQ(setup.autopilot, AutopilotFamily::ardupilot);
  EXPECT_EQ(setup.state, SetupState::blocked);                   // VISO_TYPE 0
  EXPECT_EQ(snap.vehicles[1].setup.state, SetupState::waiting);  // no heartbeat from it
  EXPECT_EQ(writes, 0U);
  const std::vector<std::string> viso{"VISO_TYPE"};
  EXPECT_FALSE(bridge.apply_setup(5, viso, t0 + seconds(8)).accepted);  // no such slot
  EXPECT_TRUE(bridge.apply_setup(0, viso, t0 + seconds(8)).accepted);
  for (int k = 81; k <= 85; ++k) tick(t0 + milliseconds(100 * k));
  EXPECT_EQ(writes, 1U);
}

TEST(BridgeVehicles, AsksForWhatTheAgreementCheckNeedsAsTheVehicle) {
  // Issue 31: the vehicle's ATTITUDE / LOCAL_POSITION_NED are asked for through on_tick, sent with
  // the vehicle's identity, counted, logged as vehicle_streams events and shown in the snapshot.
  Bridge bridge = make_bridge(two_vehicles());
  mavlink::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = kMavAutopilotArdupilot;
  const HostTime t0{seconds(100)};
  std::vector<std::pair<std::size_t, mavlink::CommandLong>> commands;
  std::vector<BridgeEvent> events;
  for (int k = 0; k <= 35; ++k) {  // 3.5 s of ticks; the vehicle's heartbeat every 0.5 s
    const HostTime now = t0 + milliseconds(100 * k);
    if (k % 5 == 0) bridge.on_vehicle_message(0, {1, 1, hb}, now);
    const BridgeOutput out = bridge.on_tick(now);
    for (const auto& c : of_type<mavlink::CommandLong>(out)) {
      if (c.second.command == 511) commands.push_back(c);
    }
    for (const auto& m : out.messages) {
      if (std::holds_alternative<mavlink::CommandLong>(m.message)) {
        EXPECT_EQ(m.frame.bytes()[5], 1);    // from the vehicle's own sysid
        EXPECT_EQ(m.frame.bytes()[6], 197);  // and our component
      }
    }
    for (const BridgeEvent& e : out.events) {
      if (e.kind == BridgeEventKind::vehicle_streams) events.push_back(e);
    }
  }
  // Only vehicle 0 has a heartbeat; after the 3 s grace, ATTITUDE first.
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].first, 0U);
  EXPECT_EQ(commands[0].second.param1, 30.0F);
  EXPECT_EQ(commands[0].second.target_system, 1);
  EXPECT_EQ(commands[0].second.target_component, 1);
  ASSERT_EQ(events.size(), 1U);  // the ticks' stream events: what was asked, once
  EXPECT_EQ(events[0].kind, BridgeEventKind::vehicle_streams);
  EXPECT_EQ(events[0].subject, "quad");
  EXPECT_EQ(events[0].text, "asking for ATTITUDE at 5 Hz (SET_MESSAGE_INTERVAL 30, 200000 us)");
  // The ACK arrives through on_vehicle_message.
  mavlink::CommandAck ack;
  ack.command = 511;
  ack.result = 0;
  const BridgeOutput acked = bridge.on_vehicle_message(0, {1, 1, ack}, t0 + milliseconds(3600));
  ASSERT_EQ(acked.events.size(), 1U);
  EXPECT_EQ(acked.events[0].text, "the vehicle accepted SET_MESSAGE_INTERVAL for ATTITUDE");
  const BridgeSnapshot snap = bridge.snapshot(t0 + milliseconds(3600));
  EXPECT_EQ(snap.vehicles[0].streams[VehicleStream::attitude].state, StreamState::accepted);
  EXPECT_EQ(snap.vehicles[0].sender.counters.interval_requests, 1U);
  EXPECT_EQ(snap.vehicles[1].streams[VehicleStream::attitude].state, StreamState::idle);
  EXPECT_EQ(snap.vehicles[1].sender.counters.interval_requests, 0U);
}

TEST(BridgeControl, RateMessagesPauseDisableAndWallClock) {
  BridgeConfig c = two_vehicles();
  c.vehicles.push_back(vehicle("spare", "Quad", Profile::px4, 3));
  c.vehicles[2].enabled = false;
  Bridge bridge = make_bridge(c);
  bridge.set_wall_clock(HostTime{seconds(100)}, 1'700'000'000'000'000);
  EXPECT_FALSE(bridge.set_rate_hz(5, 10.0));
  EXPECT_FALSE(bridge.set_rate_hz(0, -1.0));
  EXPECT_TRUE(bridge.set_rate_hz(0, 10.0));
  EXPECT_TRUE(bridge.set_paused(1, false));
  EXPECT_TRUE(bridge.set_messages(0, MessageSet{MessageKind::vision_position_estimate}));
  std::size_t vpe = 0;
  std::size_t odometry = 0;
  std::vector<mavlink::GpsInput> gps;
  for (std::uint64_t n = 1; n <= 100; ++n) {
    const BridgeOutput out = bridge.on_frame(frame_at(n, true, true), received_at(n));
    vpe += of_type<mavlink::VisionPositionEstimate>(out).size();
    odometry += of_type<mavlink::Odometry>(out).size();
    for (const auto& [v, g] : of_type<mavlink::GpsInput>(out)) gps.push_back(g);
    for (const auto& m : out.messages) EXPECT_NE(m.vehicle, 2U);  // disabled: nothing sent
  }
  EXPECT_NEAR(static_cast<double>(vpe), 10.0, 1.0);
  EXPECT_EQ(odometry, 0U);
  ASSERT_FALSE(gps.empty());
  // Wall clock known: real GPS time of the capture (week 2288 for November 2023).
  EXPECT_EQ(gps.back().time_week, 2288);
  EXPECT_GT(gps.back().time_week_ms, 252'818'000U);
  EXPECT_EQ(gps.back().yaw, 36000);  // identity attitude with +x north: nose north
  EXPECT_TRUE(bridge.set_paused(0, true));
  const BridgeOutput paused = bridge.on_frame(frame_at(200, true, true), received_at(200));
  EXPECT_TRUE(of_type<mavlink::VisionPositionEstimate>(paused).empty());
  EXPECT_TRUE(bridge.on_tick(HostTime{seconds(200)}).messages.size() >= 2U);  // heartbeats go on
  const auto s = bridge.snapshot(received_at(200));
  ASSERT_EQ(s.vehicles.size(), 3U);
  EXPECT_TRUE(s.vehicles[0].sender.paused);
  EXPECT_EQ(s.vehicles[0].sender.rate_hz, 10.0);
  EXPECT_FALSE(s.vehicles[2].enabled);
  EXPECT_EQ(s.bodies.size(), 2U);  // "spare" shares the Quad tracker
  EXPECT_EQ(s.station.frames, 101U);
}

TEST(BridgeRuntimeVehicles, AddedVehicleGetsPosesAndHeartbeatsInItsOwnSlot) {
  Bridge bridge = make_bridge(two_vehicles());
  for (std::uint64_t n = 1; n <= 50; ++n)
    (void)bridge.on_frame(frame_at(n, true, true), received_at(n));
  // A third vehicle on the tracked Quad body, and a fourth on a body nobody followed before.
  VehicleSpec spare = vehicle("spare", "Quad", Profile::px4, 3);
  spare.rate_hz = 25.0;
  auto added = bridge.add_vehicle(spare);
  ASSERT_TRUE(std::holds_alternative<std::size_t>(added));
  EXPECT_EQ(std::get<std::size_t>(added), 2U);
  auto other = bridge.add_vehicle(vehicle("other", "Other", Profile::px4, 4));
  ASSERT_TRUE(std::holds_alternative<std::size_t>(other));
  EXPECT_EQ(std::get<std::size_t>(other), 3U);
  EXPECT_EQ(bridge.vehicle_count(), 4U);
  EXPECT_EQ(bridge.find_vehicle("spare"), std::optional<std::size_t>(2));

  std::map<std::size_t, std::size_t> odometry;  // per slot
  for (std::uint64_t n = 51; n <= 150; ++n) {
    for (const auto& [slot, odo] :
         of_type<mavlink::Odometry>(bridge.on_frame(frame_at(n, true, true), received_at(n)))) {
      ++odometry[slot];
      if (slot == 2) {
        EXPECT_NEAR(odo.x, 1.0F, 1e-5F);  // the Quad's pose, already converged
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(odometry[0]), 50.0, 1.0);
  EXPECT_NEAR(static_cast<double>(odometry[2]), 25.0, 1.0);  // its own rate, from the next frame
  EXPECT_EQ(odometry.count(3), 0U);  // "Other" is never in a frame: nothing but heartbeats
  std::set<std::size_t> heartbeats;
  for (const auto& [slot, hb] : of_type<mavlink::Heartbeat>(bridge.on_tick(received_at(151)))) {
    heartbeats.insert(slot);
  }
  EXPECT_EQ(heartbeats, (std::set<std::size_t>{0, 1, 2, 3}));
  const auto s = bridge.snapshot(received_at(151));
  ASSERT_EQ(s.vehicles.size(), 4U);
  EXPECT_EQ(s.vehicles[3].index, 3U);
  EXPECT_EQ(s.vehicles[3].name, "other");
  EXPECT_EQ(s.bodies.size(), 3U);  // Quad (shared), Rover, Other
}

TEST(BridgeRuntimeVehicles, AddIsCheckedLikeMake) {
  BridgeConfig c = two_vehicles();
  c.origin.reset();
  c.vehicles.pop_back();  // the ardupilot-gps rover needs an origin
  Bridge bridge = make_bridge(c);
  auto refused = [&](const VehicleSpec& spec, const std::string& field) {
    auto added = bridge.add_vehicle(spec);
    ASSERT_TRUE(std::holds_alternative<BridgeConfigError>(added)) << field;
    EXPECT_EQ(std::get<BridgeConfigError>(added).field, field);
  };
  refused(vehicle("quad", "Other", Profile::px4, 2), "vehicle[2].name");
  refused(vehicle("gps", "Other", Profile::px4_gps, 2), "origin");
  VehicleSpec fast = vehicle("fast", "Other", Profile::px4, 2);
  fast.rate_hz = 501.0;
  refused(fast, "vehicle[2].rate_hz");
  refused(vehicle("", "Other", Profile::px4, 2), "vehicle[2].name");
  EXPECT_EQ(bridge.vehicle_count(), 1U);  // nothing half-added
  EXPECT_EQ(bridge.snapshot(HostTime{}).bodies.size(), 1U);
  // The live vehicle by slot, as added; an empty or unknown slot has none.
  ASSERT_NE(bridge.vehicle(0), nullptr);
  EXPECT_EQ(bridge.vehicle(0)->name, c.vehicles[0].name);
  EXPECT_EQ(bridge.vehicle(1), nullptr);
  ASSERT_TRUE(bridge.remove_vehicle(0));
  EXPECT_EQ(bridge.vehicle(0), nullptr);
}

TEST(BridgeRuntimeVehicles, RemovedVehicleGetsNothingAndItsSlotIsReused) {
  Bridge bridge = make_bridge(two_vehicles());
  for (std::uint64_t n = 1; n <= 20; ++n)
    (void)bridge.on_frame(frame_at(n, true, true), received_at(n));
  EXPECT_FALSE(bridge.remove_vehicle(7));
  ASSERT_TRUE(bridge.remove_vehicle(0));
  EXPECT_FALSE(bridge.remove_vehicle(0));  // already gone
  EXPECT_FALSE(bridge.find_vehicle("quad"));
  EXPECT_FALSE(bridge.set_rate_hz(0, 10.0));
  EXPECT_FALSE(bridge.set_paused(0, true));
  for (std::uint64_t n = 21; n <= 120; ++n) {
    const BridgeOutput out = bridge.on_frame(frame_at(n, true, true), received_at(n));
    for (const auto& m : out.messages) EXPECT_EQ(m.vehicle, 1U);
  }
  for (const auto& m : bridge.on_tick(received_at(121)).messages) EXPECT_EQ(m.vehicle, 1U);
  // A vehicle message for the empty slot is ignored (its link may still deliver a late frame).
  ReceivedMessage timesync{1, 1, mavlink::Timesync{0, 5, 0, 0}};
  EXPECT_TRUE(bridge.on_vehicle_message(0, timesync, received_at(121)).messages.empty());
  auto s = bridge.snapshot(received_at(121));
  ASSERT_EQ(s.vehicles.size(), 1U);
  EXPECT_EQ(s.vehicles[0].index, 1U);
  EXPECT_EQ(s.vehicles[0].name, "rover");
  ASSERT_EQ(s.bodies.size(), 1U);  // nobody follows Quad any more: its tracker is gone
  EXPECT_EQ(s.bodies[0].name, "Rover");

  // The name is free again; the lowest empty slot is reused, and the Quad is tracked anew.
  EXPECT_EQ(bridge.next_slot(), 0U);
  auto again = bridge.add_vehicle(vehicle("quad", "Quad", Profile::px4, 1));
  ASSERT_TRUE(std::holds_alternative<std::size_t>(again));
  EXPECT_EQ(std::get<std::size_t>(again), 0U);
  std::size_t odometry = 0;
  for (std::uint64_t n = 122; n <= 221; ++n) {
    for (const auto& [slot, odo] :
         of_type<mavlink::Odometry>(bridge.on_frame(frame_at(n, true, true), received_at(n)))) {
      EXPECT_EQ(slot, 0U);
      ++odometry;
    }
  }
  EXPECT_NEAR(static_cast<double>(odometry), 50.0, 2.0);
  s = bridge.snapshot(received_at(221));
  ASSERT_EQ(s.bodies.size(), 2U);
  // The rover follows a body that moved index when the Quad's tracker went: still its own pose.
  EXPECT_EQ(s.vehicles[1].body, "Rover");
  EXPECT_EQ(s.bodies[0].name, "Rover");
  EXPECT_NEAR(s.bodies[0].estimate.p_ned_m.x(), -1.0, 1e-6);

  // Removing the highest slot shrinks the table: repeated add/remove stays bounded.
  for (int i = 0; i < 1000; ++i) {
    auto slot = bridge.add_vehicle(vehicle("churn", "Churn" + std::to_string(i), Profile::px4, 9));
    ASSERT_TRUE(std::holds_alternative<std::size_t>(slot));
    ASSERT_TRUE(bridge.remove_vehicle(std::get<std::size_t>(slot)));
  }
  EXPECT_EQ(bridge.slot_count(), 2U);
  EXPECT_EQ(bridge.snapshot(received_at(221)).bodies.size(), 2U);
}

TEST(BridgeSigning, RaisedTimestampIsTheFloorOfTheNextSignedFrame) {
  BridgeConfig c = two_vehicles();
  c.vehicles[0].signing_key = std::array<std::uint8_t, 32>{7};
  Bridge bridge = make_bridge(c);
  // 2023-11-14 22:13:20 UTC → (1'700'000'000 − 1'420'070'400) s in 10 µs units.
  bridge.set_wall_clock(HostTime{seconds(100)}, 1'700'000'000'000'000);
  constexpr std::uint64_t kNow10us = 27'992'960'000'000;
  auto signing_timestamps = [](const BridgeOutput& out, std::size_t vehicle) {
    std::vector<std::uint64_t> ts;
    for (const auto& m : out.messages) {
      const auto frame = mavlink::parse_frame(m.frame.bytes());
      EXPECT_TRUE(static_cast<bool>(frame));
      if (m.vehicle != vehicle || !frame) continue;
      EXPECT_TRUE(frame->signature.has_value());
      if (frame->signature) ts.push_back(frame->signature->timestamp_10us);
    }
    return ts;
  };
  auto first = signing_timestamps(bridge.on_tick(HostTime{seconds(100)}), 0);
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first.front(), kNow10us);  // the wall clock
  // A persisted value (or a signed frame from the vehicle) 10 s ahead of the wall clock.
  EXPECT_TRUE(bridge.raise_signing_timestamp(0, kNow10us + 1'000'000));
  EXPECT_TRUE(bridge.raise_signing_timestamp(1, 5));  // unsigned vehicle: no effect, no error
  EXPECT_FALSE(bridge.raise_signing_timestamp(9, 5));
  auto next = signing_timestamps(bridge.on_frame(frame_at(1, true, true), received_at(1)), 0);
  ASSERT_FALSE(next.empty());
  EXPECT_EQ(next.front(), kNow10us + 1'000'001);
  // A lower value never lowers it.
  EXPECT_TRUE(bridge.raise_signing_timestamp(0, 1));
  next = signing_timestamps(bridge.on_frame(frame_at(3, true, true), received_at(3)), 0);
  ASSERT_FALSE(next.empty());
  EXPECT_GT(next.front(), kNow10us + 1'000'001);
}

TEST(CaptureTime, MinimumOffsetRemovesJitterAndNeverLiesInTheFuture) {
  CaptureTimeMapper mapper;
  // Frames every 10 ms, received 3..7 ms after capture (+100 s clock offset), no latency report.
  const int delays_ms[] = {5, 3, 7, 4, 6, 3, 5};
  std::optional<HostTime> previous;
  for (int i = 0; i < 7; ++i) {
    const SourceTime capture{milliseconds(10 * i)};
    const HostTime received{seconds(100) + milliseconds(10 * i + delays_ms[i])};
    const HostTime t = mapper.on_frame(capture, received, std::nullopt);
    EXPECT_LE(t, received);
    if (previous) {
      EXPECT_GT(t, *previous);
    }
    previous = t;
    if (i >= 1) {
      EXPECT_EQ(t, HostTime{seconds(100) + milliseconds(10 * i + 3)}) << i;
    }
  }
  // A source restart (its clock starts again at 0 a minute later) re-seeds instead of stalling.
  const HostTime t =
      mapper.on_frame(SourceTime{milliseconds(5)}, HostTime{seconds(160)}, std::nullopt);
  EXPECT_EQ(mapper.reseeds(), 1U);
  EXPECT_EQ(t, HostTime{seconds(160)});
}

// begin_frame + emit_frame over slot ranges + end_frame is on_frame: the same bytes to the same
// vehicles in the same order per vehicle, the same events and the same Station and body figures
// after every frame. Three ways of calling it: ranges in any order from one thread, each range
// tracking its own vehicles' bodies on demand (the daemon with one send thread),
// track_bodies() first, then the ranges (as several threads would run them), and
// track_bodies() first, then two parts of 2-slot chunks on two threads at once (the daemon with
// two send threads; Quad and Rover have vehicles in both parts). The reference is
// on_frame, and a third Bridge that runs every tracker before any vehicle (begin_frame,
// track_bodies, one range, end_frame: the order before bodies were tracked on demand) must agree
// with it too. Seven vehicles on four bodies, every profile kind, signed and decimated ones, an
// empty slot, a disabled vehicle whose body only end_frame tracks, a body lost and found again, a
// body that comes and goes with no vehicle sending for it, a vehicle removed (its body dropped,
// the next body's index shifts) and added again, and a source restart.
TEST(Bridge, FrameInStepsOverSlotRangesIsOnFrame) {
  BridgeConfig c = two_vehicles();
  c.vehicles.push_back(vehicle("q2", "Quad", Profile::classic, 3));
  c.vehicles.push_back(vehicle("r2", "Rover", Profile::px4_gps, 4));
  c.vehicles.push_back(vehicle("q3", "Quad", Profile::ardupilot, 5));
  c.vehicles.push_back(vehicle("gone", "Quad", Profile::px4, 6));
  c.vehicles.push_back(vehicle("r3", "Rover", Profile::px4, 7));
  c.vehicles.push_back(vehicle("off", "Spare", Profile::px4, 8));
  c.vehicles.push_back(vehicle("solo", "Solo", Profile::px4, 9));
  c.vehicles[2].signing_key = std::array<std::uint8_t, 32>{1};
  c.vehicles[4].rate_hz = 25.0;
  c.vehicles[7].enabled = false;
  const VehicleSpec off = c.vehicles[7];
  // Frame n; the source restarts at frame 250 (its clock 2 s back: more than loss_timeout_ms)
  // with its origin re-defined 2 m away (every body's pose jumps).
  const auto frame = [](std::uint64_t n) {
    MocapFrame f = frame_at(n, n < 100 || n > 200, true);  // Quad lost for a second
    if (n >= 250) f.capture_time -= seconds(2);
    BodySample extra = f.bodies.back();
    extra.name = "Solo";
    f.bodies.push_back(extra);
    extra.name = "Spare";
    if (n % 100 < 50) f.bodies.push_back(extra);  // Spare comes and goes
    if (n >= 250) {
      for (BodySample& b : f.bodies) b.p_world_m.x() += 2.0;
    }
    return f;
  };
  const auto same_figures = [](const BridgeSnapshot& a, const BridgeSnapshot& b) {
    EXPECT_EQ(a.station.frames, b.station.frames);
    EXPECT_EQ(a.station.last_frame_number, b.station.last_frame_number);
    EXPECT_EQ(a.station.bodies.size(), b.station.bodies.size());
    EXPECT_EQ(a.source_restarts, b.source_restarts);
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
      EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
      EXPECT_EQ(a.bodies[i].estimate.state, b.bodies[i].estimate.state);
      EXPECT_EQ(a.bodies[i].estimate.reset_counter, b.bodies[i].estimate.reset_counter);
      EXPECT_EQ(a.bodies[i].estimate.counters.accepted, b.bodies[i].estimate.counters.accepted);
      EXPECT_EQ(a.bodies[i].estimate.p_ned_m, b.bodies[i].estimate.p_ned_m);
    }
  };
  enum class Steps { on_demand, track_first, two_threads };
  for (const Steps mode : {Steps::on_demand, Steps::track_first, Steps::two_threads}) {
    SCOPED_TRACE(static_cast<int>(mode));
    Bridge whole = make_bridge(c);
    Bridge steps = make_bridge(c);
    Bridge eager = make_bridge(c);
    for (Bridge* b : {&whole, &steps, &eager}) {
      b->set_wall_clock(HostTime{seconds(100)}, 1'790'000'000'000'000);
      ASSERT_TRUE(b->remove_vehicle(5));  // "gone": an empty slot inside a range
    }
    using Bytes = std::vector<std::uint8_t>;
    std::map<std::size_t, std::vector<Bytes>> sent_whole;
    std::map<std::size_t, std::vector<Bytes>> sent_steps;
    std::map<std::size_t, std::vector<Bytes>> sent_eager;
    std::map<BridgeEventKind, std::size_t> kinds;
    BridgeOutput out;
    std::vector<OutgoingMessage> part;
    for (std::uint64_t n = 1; n <= 300; ++n) {
      if (n == 150) {  // "off" goes, and Spare with it: Solo's body index moves down by one
        for (Bridge* b : {&whole, &steps, &eager}) ASSERT_TRUE(b->remove_vehicle(7));
      }
      if (n == 170) {  // and comes back, into the lowest empty slot (5), Spare tracked again
        for (Bridge* b : {&whole, &steps, &eager}) {
          const auto added = b->add_vehicle(off);
          ASSERT_TRUE(std::holds_alternative<std::size_t>(added));
          ASSERT_EQ(std::get<std::size_t>(added), 5u);
        }
      }
      const MocapFrame f = frame(n);
      whole.on_frame(f, received_at(n), out);
      for (const auto& m : out.messages) {
        sent_whole[m.vehicle].emplace_back(m.frame.bytes().begin(), m.frame.bytes().end());
      }
      const std::vector<BridgeEvent> whole_events = out.events;
      for (const auto& e : whole_events) ++kinds[e.kind];

      eager.begin_frame(f, received_at(n), out);
      eager.track_bodies();
      part.clear();
      eager.emit_frame(0, eager.slot_count(), part);
      for (const auto& m : part) {
        sent_eager[m.vehicle].emplace_back(m.frame.bytes().begin(), m.frame.bytes().end());
      }
      eager.end_frame(out);
      ASSERT_EQ(out.events.size(), whole_events.size());

      steps.begin_frame(f, received_at(n), out);
      const auto keep = [&](const std::vector<OutgoingMessage>& messages, std::size_t first,
                            std::size_t end) {
        for (const auto& m : messages) {
          ASSERT_GE(m.vehicle, first);
          ASSERT_LT(m.vehicle, end);
          sent_steps[m.vehicle].emplace_back(m.frame.bytes().begin(), m.frame.bytes().end());
        }
      };
      if (mode == Steps::on_demand || mode == Steps::track_first) {
        if (mode == Steps::track_first) steps.track_bodies();
        // Ranges [4, 99), [2, 4), [0, 2), the way three threads might finish.
        for (const auto& [first, end] :
             {std::pair<std::size_t, std::size_t>{4, 99}, {2, 4}, {0, 2}}) {
          part.clear();
          steps.emit_frame(first, end, part);
          keep(part, first, end);
        }
      } else {
        // Two parts of 2-slot chunks: part 0 has slots 0-1, 4-5, 8-9; part 1 slots 2-3, 6-7.
        constexpr std::size_t kChunk = 2;
        constexpr std::size_t kParts = 2;
        steps.track_bodies();
        std::array<std::vector<OutgoingMessage>, kParts> parts;
        const auto run_part = [&](std::size_t p) {
          for (std::size_t first = p * kChunk; first < steps.slot_count();
               first += kParts * kChunk) {
            steps.emit_frame(first, first + kChunk, parts[p]);
          }
        };
        std::thread other(run_part, 1);
        run_part(0);
        other.join();
        for (std::size_t p = 0; p < kParts; ++p) {
          for (const auto& m : parts[p]) ASSERT_EQ(m.vehicle / kChunk % kParts, p);
          keep(parts[p], 0, steps.slot_count());
        }
      }
      steps.end_frame(out);
      ASSERT_EQ(out.messages.size(), 0u);
      ASSERT_EQ(out.events.size(), whole_events.size());
      for (std::size_t e = 0; e < whole_events.size(); ++e) {
        EXPECT_EQ(out.events[e].kind, whole_events[e].kind);
        EXPECT_EQ(out.events[e].time, whole_events[e].time);
        EXPECT_EQ(out.events[e].subject, whole_events[e].subject);
        EXPECT_EQ(out.events[e].text, whole_events[e].text);
      }
      const HostTime t = received_at(n);
      same_figures(steps.snapshot(t), whole.snapshot(t));
      same_figures(eager.snapshot(t), whole.snapshot(t));
    }
    EXPECT_GE(kinds[BridgeEventKind::body_lost], 2u);   // the Quad, and Spare in frames 50-99
    EXPECT_GE(kinds[BridgeEventKind::body_reset], 3u);  // the moved origin resets every body
    EXPECT_EQ(whole.snapshot(received_at(300)).source_restarts, 1u);
    EXPECT_EQ(sent_whole.size(), 7u);    // every live, enabled vehicle sent something
    EXPECT_EQ(sent_whole.count(5), 0u);  // "gone", then the disabled "off"
    EXPECT_EQ(sent_steps, sent_whole);
    EXPECT_EQ(sent_eager, sent_whole);
  }
}

// begin_tick + tick_vehicles over slot ranges is on_tick: the same bytes to the same vehicles in
// the same order per vehicle, and the same events, tick after tick, with frames in between. Six
// vehicles heard as PX4 and ArduPilot (heartbeats, TIMESYNC requests, the origin, the agreement
// check's stream requests, the set-up's parameter reads), one silent, a disabled one, an empty
// slot, a vehicle removed and added again; the ranges in an order threads of a chain could not
// take ([4, 99), [0, 2), [2, 4)), to show that no part depends on another.
TEST(Bridge, TickInPartsOverSlotRangesIsOnTick) {
  BridgeConfig c = two_vehicles();
  c.timesync_requests = true;
  c.vehicles.push_back(vehicle("q2", "Quad", Profile::classic, 3));
  c.vehicles.push_back(vehicle("r2", "Rover", Profile::px4_gps, 4));
  c.vehicles.push_back(vehicle("q3", "Quad", Profile::ardupilot, 5));
  c.vehicles.push_back(vehicle("gone", "Quad", Profile::px4, 6));
  c.vehicles.push_back(vehicle("silent", "Rover", Profile::px4, 7));
  c.vehicles.push_back(vehicle("off", "Quad", Profile::px4, 8));
  c.vehicles[7].enabled = false;
  const VehicleSpec gone = c.vehicles[5];
  Bridge whole = make_bridge(c);
  Bridge parts = make_bridge(c);
  using Bytes = std::vector<std::uint8_t>;
  std::map<std::size_t, std::vector<Bytes>> sent_whole;
  std::map<std::size_t, std::vector<Bytes>> sent_parts;
  std::map<std::string, std::vector<std::string>> events_whole;
  std::map<std::string, std::vector<std::string>> events_parts;
  const auto keep = [](const BridgeOutput& out, auto& sent, auto& events) {
    for (const auto& m : out.messages) {
      sent[m.vehicle].emplace_back(m.frame.bytes().begin(), m.frame.bytes().end());
    }
    for (const auto& e : out.events) events[e.subject].push_back(e.text);
  };
  std::map<std::uint32_t, std::size_t> kinds;  // message ids sent by the ticks
  BridgeOutput out;
  for (std::uint64_t n = 1; n <= 3000; ++n) {  // 30 s of 100 Hz frames, a tick every 100 ms
    const HostTime now = received_at(n);
    for (Bridge* b : {&whole, &parts}) {
      b->on_frame(frame_at(n, true, n % 1000 < 700), now, out);
      if (n % 100 == 0) {  // heartbeats of the heard vehicles, once a second
        for (const std::size_t slot : {0U, 1U, 2U, 3U, 4U, 5U}) {
          mavlink::Heartbeat hb;
          hb.type = 2;
          hb.autopilot = slot % 2 == 0 ? kMavAutopilotPx4 : kMavAutopilotArdupilot;
          b->on_vehicle_message(slot, {static_cast<std::uint8_t>(slot + 1), 1, hb}, now);
        }
      }
      if (n == 1200) {
        ASSERT_TRUE(b->remove_vehicle(5));
      }
      if (n == 2000) {
        ASSERT_TRUE(std::holds_alternative<std::size_t>(b->add_vehicle(gone)));
      }
    }
    if (n % 10 != 0) continue;
    const BridgeOutput ticked = whole.on_tick(now);
    keep(ticked, sent_whole, events_whole);
    for (const auto& m : ticked.messages) {
      ++kinds[std::visit([](const auto& msg) { return std::decay_t<decltype(msg)>::kId; },
                         m.message)];
    }
    parts.begin_tick();
    for (const auto& [first, end] : {std::pair<std::size_t, std::size_t>{4, 99}, {0, 2}, {2, 4}}) {
      parts.tick_vehicles(now, first, end, out);
      for (const auto& m : out.messages) {
        ASSERT_GE(m.vehicle, first);
        ASSERT_LT(m.vehicle, end);
      }
      keep(out, sent_parts, events_parts);
    }
  }
  EXPECT_EQ(sent_parts, sent_whole);
  EXPECT_EQ(events_parts, events_whole);
  EXPECT_EQ(sent_whole.size(), 7U);  // every enabled vehicle: heartbeats at least
  EXPECT_GT(kinds[mavlink::Heartbeat::kId], 0U);
  EXPECT_GT(kinds[mavlink::Timesync::kId], 0U);
  EXPECT_GT(kinds[mavlink::SetGpsGlobalOrigin::kId], 0U);
  EXPECT_GT(kinds[mavlink::ParamRequestRead::kId], 0U);
  EXPECT_GT(kinds[mavlink::CommandLong::kId], 0U);  // the agreement check's stream requests
  EXPECT_FALSE(events_whole.empty());
}

}  // namespace
}  // namespace mocaplink::core

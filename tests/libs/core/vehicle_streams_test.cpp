// VehicleStreams (issues 31, 28): asking a vehicle for ATTITUDE and LOCAL_POSITION_NED (and the
// estimator's health: EKF_STATUS_REPORT, ESTIMATOR_STATUS, last tests) with
// SET_MESSAGE_INTERVAL, one command at a time, confirmed by COMMAND_ACK, retried with the
// confirmation field incremented, falling back to REQUEST_DATA_STREAM on an ArduPilot that refuses
// or never answers, not asking for what arrives unasked, and asking again after a reboot. Time is
// injected: a "vehicle" here is a list of messages fed at chosen host times.
#include "mocaplink/core/vehicle_streams.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint8_t kSysid = 7;
constexpr std::uint8_t kOurCompid = 197;
constexpr std::uint8_t kAutopilotCompid = 1;

HostTime at_ms(std::int64_t ms) {
  return HostTime{milliseconds(ms)};
}

ReceivedMessage from_vehicle(mavlink::Message m) {
  return ReceivedMessage{kSysid, kAutopilotCompid, std::move(m)};
}

mavlink::CommandAck ack(std::uint8_t result) {
  mavlink::CommandAck a;
  a.command = 511;
  a.result = result;
  a.target_system = kSysid;
  a.target_component = kOurCompid;
  return a;
}

mavlink::Attitude attitude(std::uint32_t time_boot_ms) {
  mavlink::Attitude a;
  a.time_boot_ms = time_boot_ms;
  return a;
}

mavlink::LocalPositionNed position(std::uint32_t time_boot_ms) {
  mavlink::LocalPositionNed p;
  p.time_boot_ms = time_boot_ms;
  return p;
}

/// Drives one VehicleStreams with a 100 ms tick and records what it sends and logs.
struct Harness {
  VehicleStreams streams{kSysid, kOurCompid};
  StreamTarget target{true, kMavAutopilotArdupilot, kAutopilotCompid};
  std::vector<std::pair<std::int64_t, mavlink::Message>> sent;  // (ms, message)
  std::vector<std::string> notes;
  std::int64_t now_ms = 0;
  /// The vehicle sends its estimator's health by itself while its heartbeat is alive, so the
  /// tests of the agreement's two messages see only those asked for; the estimator's tests
  /// turn it off.
  bool estimator_streams = true;

  void tick_to(std::int64_t end_ms) {
    for (; now_ms <= end_ms; now_ms += 100) {
      if (estimator_streams && target.alive) receive(mavlink::EkfStatusReport{});
      std::vector<mavlink::Message> out;
      streams.on_tick(at_ms(now_ms), target, out, notes);
      for (auto& m : out) sent.emplace_back(now_ms, std::move(m));
    }
  }
  void receive(mavlink::Message m) {
    streams.on_message(from_vehicle(std::move(m)), at_ms(now_ms), notes);
  }
  [[nodiscard]] std::vector<mavlink::CommandLong> commands() const {
    std::vector<mavlink::CommandLong> out;
    for (const auto& [t, m] : sent) {
      if (const auto* c = std::get_if<mavlink::CommandLong>(&m)) out.push_back(*c);
    }
    return out;
  }
  [[nodiscard]] std::vector<mavlink::RequestDataStream> data_streams() const {
    std::vector<mavlink::RequestDataStream> out;
    for (const auto& [t, m] : sent) {
      if (const auto* r = std::get_if<mavlink::RequestDataStream>(&m)) out.push_back(*r);
    }
    return out;
  }
  [[nodiscard]] StreamState state(VehicleStream s) const { return streams.status(s).state; }
  [[nodiscard]] bool logged(const std::string& text) const {
    return std::any_of(notes.begin(), notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
  }
};

TEST(VehicleStreams, NothingIsAskedBeforeAHeartbeatNorWithinTheGracePeriod) {
  Harness h;
  h.target.alive = false;
  h.tick_to(10'000);
  EXPECT_TRUE(h.sent.empty());
  h.target.alive = true;  // first heartbeat at 10.1 s
  h.tick_to(13'000);      // grace: 3 s from the first heartbeat
  EXPECT_TRUE(h.sent.empty());
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::idle);
  h.tick_to(13'100);
  ASSERT_EQ(h.commands().size(), 1U);
}

TEST(VehicleStreams, AsksOneMessageAtATimeAndConfirmsEachWithItsAck) {
  Harness h;
  h.tick_to(3'000);  // the first request, at the end of the grace period
  auto commands = h.commands();
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].command, 511);           // MAV_CMD_SET_MESSAGE_INTERVAL
  EXPECT_EQ(commands[0].param1, 30.0F);          // ATTITUDE
  EXPECT_EQ(commands[0].param2, 200'000.0F);     // µs: 5 Hz
  EXPECT_EQ(commands[0].target_system, kSysid);  // the vehicle, its autopilot component
  EXPECT_EQ(commands[0].target_component, kAutopilotCompid);
  EXPECT_EQ(commands[0].confirmation, 0);
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::asking);
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::asking);
  h.tick_to(3'500);  // LOCAL_POSITION_NED waits: the ACK would not say which one it answers
  EXPECT_EQ(h.commands().size(), 1U);
  h.receive(ack(0));  // ACCEPTED
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::accepted);
  h.tick_to(3'600);
  commands = h.commands();
  ASSERT_EQ(commands.size(), 2U);
  EXPECT_EQ(commands[1].param1, 32.0F);  // LOCAL_POSITION_NED
  EXPECT_EQ(commands[1].confirmation, 0);
  h.receive(ack(0));
  h.receive(attitude(1000));
  h.receive(position(1000));
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::arriving);
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::arriving);
  for (std::int64_t t = 3'800; t <= 20'000; t += 200) {  // arriving: nothing more to ask
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
  }
  EXPECT_EQ(h.commands().size(), 2U);
  EXPECT_TRUE(h.data_streams().empty());
  // Logged once each: asked, accepted, arriving.
  EXPECT_TRUE(h.logged("asking for ATTITUDE at 5 Hz (SET_MESSAGE_INTERVAL 30, 200000 us)"));
  EXPECT_TRUE(h.logged("the vehicle accepted SET_MESSAGE_INTERVAL for LOCAL_POSITION_NED"));
  EXPECT_TRUE(h.logged("ATTITUDE arriving"));
}

TEST(VehicleStreams, RetriesWithTheConfirmationIncrementedThenFallsBackOnArduPilot) {
  Harness h;
  h.tick_to(30'000);  // the vehicle never answers
  const auto commands = h.commands();
  // ATTITUDE 4 times 1 s apart (confirmation 0..3), then LOCAL_POSITION_NED 4 times.
  ASSERT_EQ(commands.size(), 8U);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(commands[i].param1, i < 4 ? 30.0F : 32.0F);
    EXPECT_EQ(commands[i].confirmation, i % 4);
  }
  std::vector<std::int64_t> times;
  for (const auto& [t, m] : h.sent) {
    if (std::holds_alternative<mavlink::CommandLong>(m)) times.push_back(t);
  }
  EXPECT_EQ(times[1] - times[0], 1000);
  EXPECT_EQ(times[3] - times[2], 1000);
  // Then REQUEST_DATA_STREAM for each: EXTRA1 (10) and POSITION (6) at 5 Hz, start, 3 times each.
  const auto fallback = h.data_streams();
  ASSERT_EQ(fallback.size(), 6U);
  EXPECT_EQ(std::count_if(fallback.begin(), fallback.end(),
                          [](const auto& r) { return r.req_stream_id == 10; }),
            3);
  EXPECT_EQ(std::count_if(fallback.begin(), fallback.end(),
                          [](const auto& r) { return r.req_stream_id == 6; }),
            3);
  for (const auto& r : fallback) {
    EXPECT_EQ(r.req_message_rate, 5);
    EXPECT_EQ(r.start_stop, 1);
    EXPECT_EQ(r.target_system, kSysid);
    EXPECT_EQ(r.target_component, kAutopilotCompid);
  }
  // And still nothing: silent, with the dashboard's sentence, logged once.
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::silent);
  EXPECT_EQ(*describe_missing(VehicleStream::attitude, h.streams.status(VehicleStream::attitude)),
            "no ATTITUDE from the vehicle after asking: is this port's MAVLink enabled?");
  // ArduPilot sends LOCAL_POSITION_NED only with an EKF origin (seen against ArduCopter SITL:
  // ATTITUDE at once, LOCAL_POSITION_NED 30-40 s later): the sentence says so first.
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::silent);
  EXPECT_EQ(*describe_missing(VehicleStream::local_position_ned,
                              h.streams.status(VehicleStream::local_position_ned)),
            "no LOCAL_POSITION_NED from the vehicle after asking: it sends none until its "
            "estimator has an origin (a GPS fix, or SET_GPS_GLOBAL_ORIGIN) and a position "
            "source (see the set-up list); if ATTITUDE is missing too, is this port's MAVLink "
            "enabled?");
  EXPECT_EQ(std::count(h.notes.begin(), h.notes.end(),
                       "no ATTITUDE from the vehicle after asking: is this port's MAVLink "
                       "enabled?"),
            1);
  EXPECT_TRUE(
      h.logged("the vehicle never answered SET_MESSAGE_INTERVAL for ATTITUDE (4 tries); "
               "asking with REQUEST_DATA_STREAM EXTRA1 at 5 Hz instead"));
  // Not asked again this boot; no line per retry.
  h.tick_to(60'000);
  EXPECT_EQ(h.commands().size(), 8U);
  EXPECT_EQ(h.data_streams().size(), 6U);
  EXPECT_EQ(std::count_if(h.notes.begin(), h.notes.end(),
                          [](const std::string& n) { return n.find("asking for") == 0; }),
            2);
}

TEST(VehicleStreams, ARefusalFallsBackAtOnceAndTheFallbackStopsWhenTheMessageArrives) {
  Harness h;
  h.tick_to(3'000);
  h.receive(ack(3));  // MAV_RESULT_UNSUPPORTED
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::fallback);
  EXPECT_TRUE(
      h.logged("the vehicle refused SET_MESSAGE_INTERVAL for ATTITUDE "
               "(MAV_RESULT_UNSUPPORTED); asking with REQUEST_DATA_STREAM EXTRA1"));
  h.tick_to(3'100);
  ASSERT_EQ(h.data_streams().size(), 1U);
  EXPECT_EQ(h.data_streams()[0].req_stream_id, 10);
  h.receive(attitude(500));
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::arriving);
  EXPECT_TRUE(h.logged("ATTITUDE arriving (after REQUEST_DATA_STREAM)"));
  h.tick_to(3'200);
  ASSERT_EQ(h.commands().size(), 2U);  // LOCAL_POSITION_NED's turn
  h.receive(ack(2));                   // DENIED
  h.receive(ack(4));                   // a second ACK with nothing in flight is ignored
  h.tick_to(4'000);
  for (std::int64_t t = 4'000; t <= 10'000; t += 200) {
    h.tick_to(t);
    h.receive(position(static_cast<std::uint32_t>(t)));
    h.receive(attitude(static_cast<std::uint32_t>(t)));
  }
  const auto fallback = h.data_streams();
  // EXTRA1 once (ATTITUDE came), POSITION once (it came before the second).
  EXPECT_EQ(fallback.size(), 2U);
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::arriving);
}

TEST(VehicleStreams, TemporarilyRejectedIsRetriedAndAckForSomeoneElseIsIgnored) {
  Harness h;
  h.tick_to(3'000);
  h.receive(ack(1));  // TEMPORARILY_REJECTED: the next attempt as scheduled
  mavlink::CommandAck other = ack(0);
  other.target_component = 190;  // a ground station's own request
  h.receive(other);
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::asking);
  h.tick_to(4'000);
  ASSERT_EQ(h.commands().size(), 2U);
  EXPECT_EQ(h.commands()[1].param1, 30.0F);
  EXPECT_EQ(h.commands()[1].confirmation, 1);
  h.receive(ack(0));
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::accepted);
}

TEST(VehicleStreams, AVehicleThatIsNotArduPilotIsNotSentRequestDataStream) {
  Harness h;
  h.target.autopilot = kMavAutopilotPx4;
  h.tick_to(3'000);
  h.receive(ack(4));  // FAILED
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::refused);
  EXPECT_EQ(*describe_missing(VehicleStream::attitude, h.streams.status(VehicleStream::attitude)),
            "the vehicle refused SET_MESSAGE_INTERVAL for ATTITUDE (MAV_RESULT_FAILED): no "
            "ATTITUDE, so the agreement cannot be checked (asked again after a reboot)");
  h.tick_to(30'000);
  EXPECT_TRUE(h.data_streams().empty());
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::refused);  // never answered
  EXPECT_EQ(h.commands().size(), 5U);  // 1 for ATTITUDE, 4 for LOCAL_POSITION_NED
}

TEST(VehicleStreams, MessagesThatArriveUnaskedAreNotAskedFor) {
  Harness h;
  for (std::int64_t t = 0; t <= 20'000; t += 100) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));  // PX4's onboard mode streams ATTITUDE
  }
  const auto commands = h.commands();
  ASSERT_FALSE(commands.empty());  // only for the one that does not arrive (never answered here)
  for (const auto& c : commands) EXPECT_EQ(c.param1, 32.0F);
  EXPECT_FALSE(h.logged("asking for ATTITUDE"));
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::arriving);
  EXPECT_FALSE(h.streams.status(VehicleStream::attitude).asked);
}

TEST(VehicleStreams, ARebootSeenOnTheBootClockAsksAgain) {
  Harness h;
  h.tick_to(3'000);
  h.receive(ack(0));
  h.tick_to(3'100);
  h.receive(ack(0));
  for (std::int64_t t = 3'200; t <= 10'000; t += 200) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t + 60'000)));
    h.receive(position(static_cast<std::uint32_t>(t + 60'000)));
  }
  ASSERT_EQ(h.commands().size(), 2U);
  // The vehicle restarts: its rates are gone, its boot clock starts again. One ATTITUDE from the
  // new boot (a default stream of its own, say) is enough to see it.
  h.receive(attitude(800));
  EXPECT_EQ(h.streams.snapshot().reboots, 1U);
  EXPECT_TRUE(h.logged("the vehicle rebooted (its boot clock went back from 70.0 s to 0.8 s)"));
  EXPECT_EQ(h.state(VehicleStream::local_position_ned), StreamState::idle);
  EXPECT_FALSE(h.streams.status(VehicleStream::local_position_ned).asked);
  ASSERT_EQ(h.now_ms, 10'100);  // seen at 10.1 s: a new grace period until 13.1 s
  h.tick_to(13'000);
  EXPECT_EQ(h.commands().size(), 2U);
  h.tick_to(13'100);  // both again (ATTITUDE did not keep arriving either), one at a time
  ASSERT_EQ(h.commands().size(), 3U);
  EXPECT_EQ(h.commands()[2].param1, 30.0F);
  EXPECT_EQ(h.commands()[2].confirmation, 0);
  h.receive(ack(0));
  h.tick_to(13'200);
  ASSERT_EQ(h.commands().size(), 4U);
  EXPECT_EQ(h.commands()[3].param1, 32.0F);
}

TEST(VehicleStreams, ARebootSeenOnTheTimesyncClockAsksAgainAtOnceAfterGrace) {
  Harness h;
  auto answer = [](std::int64_t vehicle_ms) {
    mavlink::Timesync t;
    t.tc1 = vehicle_ms * 1'000'000;  // the vehicle's clock in an answer to our request
    t.ts1 = 123;
    return mavlink::Message{t};
  };
  h.tick_to(3'000);
  h.receive(ack(0));
  h.tick_to(3'100);
  h.receive(ack(0));
  h.receive(answer(50'000));
  h.receive(answer(51'000));
  h.receive(answer(49'500));  // 1.5 s back: a reordered or odd sample, not a reboot
  EXPECT_EQ(h.streams.snapshot().reboots, 0U);
  h.receive(answer(1'000));  // 48.5 s back: a reboot
  EXPECT_EQ(h.streams.snapshot().reboots, 1U);
  // From another component of the same system (a companion's clock): not the vehicle's boot.
  mavlink::Timesync companion;
  companion.tc1 = 5;
  h.streams.on_message(ReceivedMessage{kSysid, 191, companion}, at_ms(h.now_ms), h.notes);
  EXPECT_EQ(h.streams.snapshot().reboots, 1U);
  h.tick_to(6'200);
  EXPECT_EQ(h.commands().size(), 3U);  // asked again after the new grace period
}

TEST(VehicleStreams, AStreamThatStopsIsAskedForAgainButASilentLinkIsNot) {
  Harness h;
  for (std::int64_t t = 0; t <= 5'000; t += 100) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
  }
  EXPECT_TRUE(h.commands().empty());
  // The heartbeat goes too (link down): nothing is asked while it is silent...
  h.target.alive = false;
  h.tick_to(20'000);
  EXPECT_TRUE(h.commands().empty());
  // ...and when it is back, the messages get their chance first.
  h.target.alive = true;
  h.tick_to(22'900);
  EXPECT_TRUE(h.commands().empty());
  h.tick_to(23'200);
  ASSERT_EQ(h.commands().size(), 1U);
  EXPECT_TRUE(h.logged("ATTITUDE stopped arriving; asking again"));
}

TEST(VehicleStreams, ArduPilotIsAskedForEkfStatusReportAtOneHertzAfterTheAgreementsTwo) {
  Harness h;
  h.estimator_streams = false;
  h.tick_to(3'000);
  h.receive(ack(0));
  h.tick_to(3'100);
  h.receive(ack(0));
  h.receive(attitude(3'100));
  h.receive(position(3'100));
  h.tick_to(3'200);
  auto commands = h.commands();
  ASSERT_EQ(commands.size(), 3U);
  EXPECT_EQ(commands[2].param1, 193.0F);        // EKF_STATUS_REPORT
  EXPECT_EQ(commands[2].param2, 1'000'000.0F);  // µs: 1 Hz
  EXPECT_EQ(h.state(VehicleStream::estimator), StreamState::asking);
  EXPECT_TRUE(
      h.logged("asking for EKF_STATUS_REPORT at 1 Hz (SET_MESSAGE_INTERVAL 193, "
               "1000000 us)"));
  // Never answered: REQUEST_DATA_STREAM EXTRA3 (ArduPilot's group with it) at 1 Hz.
  for (std::int64_t t = 3'200; t <= 20'000; t += 200) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
  }
  EXPECT_EQ(h.commands().size(), 6U);  // 4 tries for EKF_STATUS_REPORT
  const auto fallback = h.data_streams();
  ASSERT_EQ(fallback.size(), 3U);
  for (const auto& r : fallback) {
    EXPECT_EQ(r.req_stream_id, 12);
    EXPECT_EQ(r.req_message_rate, 1);
  }
  EXPECT_TRUE(
      h.logged("the vehicle never answered SET_MESSAGE_INTERVAL for EKF_STATUS_REPORT "
               "(4 tries); asking with REQUEST_DATA_STREAM EXTRA3 at 1 Hz instead"));
  EXPECT_EQ(h.state(VehicleStream::estimator), StreamState::silent);
  EXPECT_EQ(*describe_missing(VehicleStream::estimator, h.streams.status(VehicleStream::estimator),
                              kMavAutopilotArdupilot),
            "no EKF_STATUS_REPORT from the vehicle after asking: its firmware may not send it "
            "on this port");
  // It comes after all: arriving, and nothing more is asked.
  h.receive(mavlink::EkfStatusReport{});
  EXPECT_EQ(h.state(VehicleStream::estimator), StreamState::arriving);
}

TEST(VehicleStreams, Px4IsAskedForEstimatorStatusAndARefusalIsSaidInWords) {
  Harness h;
  h.estimator_streams = false;
  h.target.autopilot = kMavAutopilotPx4;
  for (std::int64_t t = 0; t <= 3'200; t += 100) {  // PX4's onboard mode streams both
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
  }
  const auto commands = h.commands();
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].param1, 230.0F);  // ESTIMATOR_STATUS
  EXPECT_EQ(commands[0].param2, 1'000'000.0F);
  h.receive(ack(3));  // UNSUPPORTED
  EXPECT_EQ(h.state(VehicleStream::estimator), StreamState::refused);
  EXPECT_EQ(*describe_missing(VehicleStream::estimator, h.streams.status(VehicleStream::estimator),
                              kMavAutopilotPx4),
            "the vehicle refused SET_MESSAGE_INTERVAL for ESTIMATOR_STATUS "
            "(MAV_RESULT_UNSUPPORTED): no ESTIMATOR_STATUS, so the estimator's flags are unknown "
            "(asked again after a reboot)");
  h.tick_to(20'000);
  EXPECT_TRUE(h.data_streams().empty());  // no fallback on PX4
}

TEST(VehicleStreams, AnotherAutopilotIsNeverAskedForItsEstimator) {
  Harness h;
  h.estimator_streams = false;
  h.target.autopilot = 0;  // MAV_AUTOPILOT_GENERIC: which message would it be?
  for (std::int64_t t = 0; t <= 30'000; t += 100) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
  }
  EXPECT_TRUE(h.commands().empty());
  EXPECT_EQ(h.state(VehicleStream::estimator), StreamState::idle);
  EXPECT_FALSE(asked_of(VehicleStream::estimator, 0));
  EXPECT_TRUE(asked_of(VehicleStream::attitude, 0));
}

TEST(VehicleStreams, RawImuIsAskedOfAnArduPilotOnlyWhileItsHeadingIsWanted) {
  // Issue 48: RAW_IMU (its compass's field) is the nose's one reference where EKF3 takes yaw
  // from mocap; it is asked for only then.
  Harness h;
  const auto feed = [&h](std::int64_t to_ms) {
    for (std::int64_t t = h.now_ms; t <= to_ms; t += 100) {
      h.tick_to(t);
      h.receive(attitude(static_cast<std::uint32_t>(t)));
      h.receive(position(static_cast<std::uint32_t>(t)));
    }
  };
  feed(10'000);
  EXPECT_TRUE(h.commands().empty());  // not wanted: never asked
  EXPECT_EQ(h.state(VehicleStream::heading), StreamState::idle);
  h.target.want_heading = true;
  feed(10'300);
  auto commands = h.commands();
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].param1, 27.0F);       // RAW_IMU
  EXPECT_EQ(commands[0].param2, 500'000.0F);  // µs: 2 Hz
  EXPECT_TRUE(h.logged("asking for RAW_IMU at 2 Hz (SET_MESSAGE_INTERVAL 27, 500000 us)"));
  h.receive(ack(0));
  h.receive(mavlink::RawImu{});
  EXPECT_EQ(h.state(VehicleStream::heading), StreamState::arriving);
  // No longer wanted (the set-up list now reads EK3_SRC1_YAW = 1): when it stops it is not
  // asked for again.
  h.target.want_heading = false;
  feed(20'000);
  EXPECT_EQ(h.commands().size(), 1U);
  EXPECT_EQ(data_stream_id(VehicleStream::heading), 1);  // RAW_SENSORS on ArduPilot
  EXPECT_EQ(data_stream_name(VehicleStream::heading), "RAW_SENSORS");
  EXPECT_TRUE(asked_of(VehicleStream::heading, kMavAutopilotArdupilot));
  EXPECT_TRUE(asked_of(VehicleStream::heading, kMavAutopilotPx4));
  EXPECT_FALSE(asked_of(VehicleStream::heading, 0));
}

TEST(VehicleStreams, Px4IsAskedForHighresImuInstead) {
  // PX4 sends no RAW_IMU; its magnetometer's field is in HIGHRES_IMU (105).
  Harness h;
  h.estimator_streams = false;
  h.target.autopilot = kMavAutopilotPx4;
  h.target.want_heading = true;
  for (std::int64_t t = 0; t <= 3'300; t += 100) {
    h.tick_to(t);
    h.receive(attitude(static_cast<std::uint32_t>(t)));
    h.receive(position(static_cast<std::uint32_t>(t)));
    h.receive(mavlink::EstimatorStatus{});
  }
  const auto commands = h.commands();
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].param1, 105.0F);
  EXPECT_EQ(commands[0].param2, 500'000.0F);
  EXPECT_EQ(mavlink_name(VehicleStream::heading, kMavAutopilotPx4), "HIGHRES_IMU");
  h.receive(ack(0));
  h.receive(mavlink::HighresImu{});
  EXPECT_EQ(h.state(VehicleStream::heading), StreamState::arriving);
}

TEST(VehicleStreams, MessagesFromOtherSystemsCountForNothing) {
  Harness h;
  h.tick_to(2'000);
  h.streams.on_message(ReceivedMessage{8, 1, attitude(100)}, at_ms(h.now_ms), h.notes);
  mavlink::CommandAck a = ack(0);
  h.tick_to(3'000);
  h.streams.on_message(ReceivedMessage{8, 1, a}, at_ms(h.now_ms), h.notes);
  EXPECT_EQ(h.state(VehicleStream::attitude), StreamState::asking);
}

}  // namespace
}  // namespace mocaplink::core

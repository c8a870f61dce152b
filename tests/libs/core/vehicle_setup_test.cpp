// VehicleSetup (issue 28): identifying the autopilot, reading the profile's parameters one at a
// time, paced and retried, decoding PX4's bytewise and ArduPilot's cast integers, the check list,
// writing fixes only on request (and never to an armed vehicle), STATUSTEXT and estimator health.
// Time is injected: the "vehicle" is a script of answers fed at chosen host times. The parameter
// encodings are the ones PX4 (mavlink_parameters.cpp: memcpy of the int32) and ArduPilot
// (GCS_Param.cpp: cast_to_float) send.
#include "mocaplink/core/vehicle_setup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

constexpr std::uint8_t kSysid = 7;
constexpr std::uint8_t kOurCompid = 197;
constexpr std::uint8_t kAutopilotCompid = 1;
constexpr std::uint8_t kInt32 = 6;
constexpr std::uint8_t kInt8 = 2;
constexpr std::uint8_t kInt16 = 4;
constexpr std::uint8_t kReal32 = 9;

HostTime at_ms(std::int64_t ms) {
  return HostTime{milliseconds(ms)};
}

std::string id_of(const std::array<char, 16>& id) {
  return {id.begin(), std::find(id.begin(), id.end(), '\0')};
}

/// A scripted vehicle: answers AUTOPILOT_VERSION and PARAM_REQUEST_READ / PARAM_SET from a table,
/// encoding values as its autopilot does.
struct Vehicle {
  bool px4 = true;
  std::uint32_t version = 0x010E03FFu;  // 1.14.3
  std::map<std::string, std::pair<double, std::uint8_t>> params;
  bool answers = true;
  bool accepts_writes = true;

  [[nodiscard]] mavlink::ParamValue value(const std::string& name) const {
    const auto& [v, type] = params.at(name);
    mavlink::ParamValue m;
    std::memcpy(m.param_id.data(), name.data(), std::min<std::size_t>(name.size(), 16));
    m.param_type = type;
    m.param_index = 65535;
    if (px4 && type != kReal32) {
      m.param_value = std::bit_cast<float>(static_cast<std::int32_t>(v));
    } else {
      m.param_value = static_cast<float>(v);
    }
    return m;
  }

  /// The answers to what mocaplink sent.
  std::vector<mavlink::Message> answer(const mavlink::Message& sent) {
    std::vector<mavlink::Message> out;
    if (!answers) return out;
    if (const auto* c = std::get_if<mavlink::CommandLong>(&sent)) {
      if (c->command == 512 && c->param1 == 148.0F && version != 0) {
        mavlink::AutopilotVersion v;
        v.flight_sw_version = version;
        v.capabilities = px4 ? (2 | 16) : 2;  // what each sets (PARAM_FLOAT, ENCODE_BYTEWISE)
        out.emplace_back(v);
      }
    } else if (const auto* r = std::get_if<mavlink::ParamRequestRead>(&sent)) {
      const std::string name = id_of(r->param_id);
      // Every firmware has its compass parameters (read for the agreement's second heading,
      // estimate_sources.hpp): answered as a vehicle with a calibrated compass unless the table
      // says (SITL's copter.parm offsets).
      if (params.count(name) == 0) {
        static const std::map<std::string, std::pair<double, std::uint8_t>> kPx4{
            {"SYS_HAS_MAG", {1, kInt32}}, {"EKF2_MAG_DECL", {0, kReal32}}};
        static const std::map<std::string, std::pair<double, std::uint8_t>> kArdu{
            {"COMPASS_ENABLE", {1, kInt8}},
            {"COMPASS_OFS_X", {5, kReal32}},
            {"COMPASS_OFS_Y", {13, kReal32}},
            {"COMPASS_OFS_Z", {-18, kReal32}},
            {"COMPASS_DEC", {0, kReal32}}};
        const auto& defaults = px4 ? kPx4 : kArdu;
        if (const auto it = defaults.find(name); it != defaults.end()) params[name] = it->second;
      }
      if (params.count(name) != 0) out.emplace_back(value(name));  // unknown: silence (both)
    } else if (const auto* s = std::get_if<mavlink::ParamSet>(&sent)) {
      const std::string name = id_of(s->param_id);
      if (params.count(name) == 0) return out;
      auto& [v, type] = params[name];
      if (accepts_writes) {
        v = px4 && type != kReal32 ? std::bit_cast<std::int32_t>(s->param_value)
                                   : static_cast<double>(s->param_value);
      }
      out.emplace_back(value(name));
    }
    return out;
  }
};

struct Harness {
  VehicleSetup setup{kSysid, kOurCompid, Profile::px4, MessageSet{MessageKind::odometry}};
  Vehicle vehicle;
  SetupTarget target{true, kMavAutopilotPx4, kAutopilotCompid, false};
  DelayInputs delay;
  std::vector<std::pair<std::int64_t, mavlink::Message>> sent;
  std::vector<std::string> notes;
  std::int64_t now_ms = 0;

  void feed(const mavlink::Message& m) {
    setup.on_message(ReceivedMessage{kSysid, kAutopilotCompid, m}, at_ms(now_ms), notes);
  }
  /// Ticks every 100 ms for `ms`, answering each request 20 ms later.
  void run(std::int64_t ms) {
    const std::int64_t end = now_ms + ms;
    while (now_ms < end) {
      std::vector<mavlink::Message> out;
      setup.on_tick(at_ms(now_ms), target, delay, out, notes);
      for (const auto& m : out) {
        sent.emplace_back(now_ms, m);
        now_ms += 20;
        for (const auto& a : vehicle.answer(m)) feed(a);
        now_ms -= 20;
      }
      now_ms += 100;
    }
  }
  template <typename M>
  [[nodiscard]] std::vector<std::int64_t> times_of() const {
    std::vector<std::int64_t> t;
    for (const auto& [ms, m] : sent) {
      if (std::holds_alternative<M>(m)) t.push_back(ms);
    }
    return t;
  }
  [[nodiscard]] const SetupLine* line(const std::string& name) const {
    static VehicleSetupSnapshot snap;
    snap = setup.snapshot();
    for (const SetupLine& l : snap.lines) {
      if (l.item.parameter == name) return &l;
    }
    return nullptr;
  }
};

/// A PX4 1.14 vehicle with EKF2 left at its defaults for GPS flight (EV off, baro height).
void px4_defaults(Vehicle& v) {
  v.params = {{"EKF2_EV_CTRL", {0, kInt32}},
              {"EKF2_HGT_REF", {0, kInt32}},
              {"EKF2_GPS_CTRL", {7, kInt32}},
              {"EKF2_MAG_TYPE", {0, kInt32}},
              {"EKF2_EV_DELAY", {0, kReal32}}};
}

TEST(VehicleSetup, NothingBeforeAHeartbeat) {
  Harness h;
  h.target.alive = false;
  h.run(5000);
  EXPECT_TRUE(h.sent.empty());
  EXPECT_EQ(h.setup.state(), SetupState::waiting);
}

TEST(VehicleSetup, ReadsEachParameterOnceAndFindsTheWrongOnes) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  const auto snap = h.setup.snapshot();
  EXPECT_EQ(snap.autopilot, AutopilotFamily::px4);
  ASSERT_TRUE(snap.version);
  EXPECT_EQ(to_string(*snap.version), "1.14.3");
  // One each, all answered: the 5 of the list, SYS_HAS_MAG and EKF2_MAG_DECL (the agreement's
  // second heading).
  EXPECT_EQ(h.times_of<mavlink::ParamRequestRead>().size(), 7U);
  EXPECT_EQ(snap.state, SetupState::blocked);
  const SetupLine* ev = h.line("EKF2_EV_CTRL");
  ASSERT_NE(ev, nullptr);
  EXPECT_EQ(ev->item.current, 0.0);
  EXPECT_EQ(ev->item.status, SetupStatus::wrong);
  EXPECT_EQ(ev->item.severity, SetupSeverity::blocks);
  EXPECT_EQ(ev->item.fix, 15.0);
  EXPECT_EQ(h.line("EKF2_GPS_CTRL")->item.current, 7.0);  // bytewise int32 decoded
  // The log names the wrong ones (blocks and degrades, not advice).
  const auto blocked = std::find_if(h.notes.begin(), h.notes.end(), [](const std::string& n) {
    return n.rfind("set-up blocked", 0) == 0;
  });
  ASSERT_NE(blocked, h.notes.end());
  EXPECT_NE(blocked->find("EKF2_EV_CTRL is 0, needs 15"), std::string::npos) << *blocked;
  EXPECT_NE(blocked->find("EKF2_HGT_REF"), std::string::npos);
  EXPECT_EQ(blocked->find("EKF2_GPS_CTRL"), std::string::npos);
}

TEST(VehicleSetup, RequestsArePacedOneInFlight) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  const auto t = h.times_of<mavlink::ParamRequestRead>();
  for (std::size_t i = 1; i < t.size(); ++i) {
    EXPECT_GE(t[i] - t[i - 1], 100) << i;  // kParamGap after each answer
  }
}

TEST(VehicleSetup, AMissingParameterIsAskedThreeTimesThenMissing) {
  Harness h;
  px4_defaults(h.vehicle);
  h.vehicle.params.erase("EKF2_EV_CTRL");  // e.g. a build without it
  h.run(6000);
  EXPECT_EQ(h.times_of<mavlink::ParamRequestRead>().size(), 6U + kParamAttempts);
  const SetupLine* ev = h.line("EKF2_EV_CTRL");
  ASSERT_NE(ev, nullptr);
  EXPECT_EQ(ev->item.status, SetupStatus::missing);
  EXPECT_EQ(h.setup.state(), SetupState::blocked);
}

TEST(VehicleSetup, NoAnswerAtAll) {
  Harness h;
  px4_defaults(h.vehicle);
  h.vehicle.answers = false;
  h.run(30000);
  EXPECT_EQ(h.times_of<mavlink::CommandLong>().size(), kVersionAttempts);
  EXPECT_EQ(h.setup.state(), SetupState::no_answer);
  EXPECT_EQ(h.times_of<mavlink::ParamRequestRead>().size(), 7U * kParamAttempts);
  EXPECT_TRUE(std::any_of(h.notes.begin(), h.notes.end(), [](const std::string& n) {
    return n.find("newest firmware's parameter names") != std::string::npos;
  }));
}

TEST(VehicleSetup, Px4_113GetsTheOldNames) {
  Harness h;
  h.vehicle.version = 0x010D02FFu;
  h.vehicle.params = {{"EKF2_AID_MASK", {1, kInt32}},
                      {"EKF2_HGT_MODE", {0, kInt32}},
                      {"EKF2_MAG_TYPE", {5, kInt32}},
                      {"EKF2_EV_DELAY", {0, kReal32}}};
  h.run(3000);
  EXPECT_EQ(h.setup.state(), SetupState::blocked);
  EXPECT_EQ(h.line("EKF2_AID_MASK")->item.fix, 281.0);
  EXPECT_EQ(h.line("EKF2_EV_CTRL"), nullptr);
}

TEST(VehicleSetup, ArduPilotCastIntegers) {
  Harness h;
  h.vehicle.px4 = false;
  h.vehicle.version = 0x04070000u;  // 4.7.0-dev
  h.setup = VehicleSetup(kSysid, kOurCompid, Profile::ardupilot, MessageSet{MessageKind::odometry});
  h.target.autopilot = kMavAutopilotArdupilot;
  h.vehicle.params = {{"AHRS_EKF_TYPE", {3, kInt8}},   {"VISO_TYPE", {0, kInt8}},
                      {"EK3_SRC1_POSXY", {3, kInt8}},  {"EK3_SRC1_VELXY", {3, kInt8}},
                      {"EK3_SRC1_POSZ", {1, kInt8}},   {"EK3_SRC1_VELZ", {3, kInt8}},
                      {"EK3_SRC1_YAW", {1, kInt8}},    {"GPS1_TYPE", {1, kInt8}},
                      {"VISO_DELAY_MS", {10, kInt16}}, {"COMPASS_ENABLE", {1, kInt8}},
                      {"COMPASS_OFS_X", {0, kReal32}}};
  h.run(4000);
  EXPECT_EQ(h.setup.state(), SetupState::blocked);
  // Read for the agreement check's second heading (estimate_sources.hpp), with no line.
  EXPECT_EQ(h.setup.parameter("COMPASS_ENABLE"), 1.0);
  EXPECT_EQ(h.setup.parameter("COMPASS_OFS_X"), 0.0);
  EXPECT_EQ(h.setup.parameter("COMPASS_OFS_Z"), -18.0);
  EXPECT_EQ(h.line("COMPASS_OFS_X"), nullptr);
  EXPECT_EQ(h.line("VISO_TYPE")->item.current, 0.0);
  EXPECT_EQ(h.line("VISO_TYPE")->item.severity, SetupSeverity::blocks);
  EXPECT_EQ(h.line("AHRS_EKF_TYPE")->item.status, SetupStatus::ok);
  EXPECT_EQ(h.line("VISO_DELAY_MS")->item.status, SetupStatus::unmeasured);
  EXPECT_EQ(h.line("VISO_DELAY_MS")->item.current, 10.0);
}

TEST(VehicleSetup, ApplyWritesOnlyWhatWasNamedAndConfirmsIt) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  ASSERT_TRUE(h.times_of<mavlink::ParamSet>().empty());  // nothing written unasked
  const std::vector<std::string> names{"EKF2_EV_CTRL", "EKF2_HGT_REF"};
  const SetupRequestResult r = h.setup.apply(names, at_ms(h.now_ms));
  EXPECT_TRUE(r.accepted) << r.message;
  h.run(2000);
  EXPECT_EQ(h.times_of<mavlink::ParamSet>().size(), 2U);
  EXPECT_EQ(h.vehicle.params["EKF2_EV_CTRL"].first, 15.0);
  EXPECT_EQ(h.vehicle.params["EKF2_HGT_REF"].first, 3.0);
  EXPECT_EQ(h.vehicle.params["EKF2_MAG_TYPE"].first, 0.0);  // advice, not named: untouched
  EXPECT_EQ(h.line("EKF2_EV_CTRL")->apply, ApplyState::confirmed);
  EXPECT_EQ(h.line("EKF2_EV_CTRL")->item.status, SetupStatus::ok);
  EXPECT_EQ(h.setup.state(), SetupState::ready);
  // EKF2_HGT_REF takes effect after a reboot: said so.
  const auto snap = h.setup.snapshot();
  EXPECT_EQ(snap.reboot_for, std::vector<std::string>{"EKF2_HGT_REF"});
}

TEST(VehicleSetup, ApplyRefusals) {
  Harness h;
  px4_defaults(h.vehicle);
  const std::vector<std::string> ev{"EKF2_EV_CTRL"};
  EXPECT_FALSE(h.setup.apply(ev, at_ms(0)).accepted);  // nothing read yet
  h.run(3000);
  const std::vector<std::string> unseen{"EKF2_EV_CTRL", "COM_ARM_WO_GPS"};
  EXPECT_FALSE(h.setup.apply(unseen, at_ms(h.now_ms)).accepted);  // not on the list
  const std::vector<std::string> fine{"EKF2_EV_DELAY"};
  EXPECT_FALSE(h.setup.apply(fine, at_ms(h.now_ms)).accepted);  // nothing to fix
  EXPECT_FALSE(h.setup.apply({}, at_ms(h.now_ms)).accepted);
  h.target.armed = true;
  h.run(200);
  const SetupRequestResult armed = h.setup.apply(ev, at_ms(h.now_ms));
  EXPECT_FALSE(armed.accepted);
  EXPECT_NE(armed.message.find("armed"), std::string::npos);
  h.run(2000);
  EXPECT_TRUE(h.times_of<mavlink::ParamSet>().empty());
  std::vector<mavlink::Message> out;
  EXPECT_FALSE(h.setup.reboot(at_ms(h.now_ms), out).accepted);
  EXPECT_TRUE(out.empty());
}

TEST(VehicleSetup, ARefusedRebootIsSaidNotTakenAsDone) {
  // PX4 SITL answers MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN with DENIED (a posix build has no reset);
  // the API said 200 "reboot asked" and nothing more.
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  mavlink::CommandAck denied;
  denied.command = 246;
  denied.result = 2;  // MAV_RESULT_DENIED
  denied.target_system = kSysid;
  denied.target_component = kOurCompid;
  h.feed(denied);  // not asked: not ours
  EXPECT_EQ(h.setup.snapshot().last_refusal, "");
  std::vector<mavlink::Message> out;
  ASSERT_TRUE(h.setup.reboot(at_ms(h.now_ms), out).accepted);
  mavlink::CommandAck other = denied;
  other.target_component = 190;  // a ground station's reboot
  h.feed(other);
  EXPECT_EQ(h.setup.snapshot().last_refusal, "");
  mavlink::CommandAck progress = denied;
  progress.result = 5;  // IN_PROGRESS: wait for the final answer
  h.feed(progress);
  EXPECT_EQ(h.setup.snapshot().last_refusal, "");
  h.feed(denied);
  EXPECT_EQ(h.setup.snapshot().last_refusal,
            "the vehicle refused the reboot (MAV_RESULT_DENIED): restart it by hand for the "
            "changes that wait for a reboot");
  EXPECT_NE(std::find(h.notes.begin(), h.notes.end(), h.setup.snapshot().last_refusal),
            h.notes.end());
  // Asked again and accepted: no refusal.
  ASSERT_TRUE(h.setup.reboot(at_ms(h.now_ms), out).accepted);
  EXPECT_EQ(h.setup.snapshot().last_refusal, "");
  mavlink::CommandAck accepted = denied;
  accepted.result = 0;
  h.feed(accepted);
  EXPECT_EQ(h.setup.snapshot().last_refusal, "");
}

TEST(VehicleSetup, AnArmedHeartbeatRefusesAtOnceWithoutATick) {
  // The dashboard's request can come between the heartbeat that says armed and the next tick.
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  mavlink::Heartbeat armed;
  armed.type = 2;
  armed.autopilot = kMavAutopilotPx4;
  armed.base_mode = kMavModeFlagSafetyArmed;
  h.feed(armed);
  const std::vector<std::string> ev{"EKF2_EV_CTRL"};
  EXPECT_FALSE(h.setup.apply(ev, at_ms(h.now_ms)).accepted);
  std::vector<mavlink::Message> out;
  EXPECT_FALSE(h.setup.reboot(at_ms(h.now_ms), out).accepted);
  // A ground station's heartbeat on the vehicle's system id says nothing about arming.
  mavlink::Heartbeat gcs = armed;
  gcs.type = 6;
  gcs.base_mode = 0;
  h.feed(gcs);
  EXPECT_FALSE(h.setup.apply(ev, at_ms(h.now_ms)).accepted);
}

TEST(VehicleSetup, AValueAnnouncedBeforeTheWriteIsNotItsAnswer) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  const std::vector<std::string> ev{"EKF2_EV_CTRL"};
  ASSERT_TRUE(h.setup.apply(ev, at_ms(h.now_ms)).accepted);
  h.feed(h.vehicle.value("EKF2_EV_CTRL"));  // a broadcast of the old value, before any PARAM_SET
  EXPECT_EQ(h.line("EKF2_EV_CTRL")->apply, ApplyState::pending);
  h.run(1000);
  EXPECT_EQ(h.times_of<mavlink::ParamSet>().size(), 1U);
  EXPECT_EQ(h.line("EKF2_EV_CTRL")->apply, ApplyState::confirmed);
}

TEST(VehicleSetup, AVehicleThatKeepsItsValueFailsTheItem) {
  Harness h;
  px4_defaults(h.vehicle);
  h.vehicle.accepts_writes = false;
  h.run(3000);
  const std::vector<std::string> ev{"EKF2_EV_CTRL"};
  ASSERT_TRUE(h.setup.apply(ev, at_ms(h.now_ms)).accepted);
  h.run(2000);
  const SetupLine* l = h.line("EKF2_EV_CTRL");
  EXPECT_EQ(l->apply, ApplyState::failed);
  EXPECT_EQ(l->apply_note, "the vehicle kept 0");
  EXPECT_EQ(l->item.status, SetupStatus::wrong);
}

TEST(VehicleSetup, ArmingStopsTheWrites) {
  Harness h;
  px4_defaults(h.vehicle);
  h.vehicle.answers = true;
  h.run(3000);
  h.vehicle.answers = false;  // writes go unanswered...
  const std::vector<std::string> two{"EKF2_EV_CTRL", "EKF2_HGT_REF"};
  ASSERT_TRUE(h.setup.apply(two, at_ms(h.now_ms)).accepted);
  h.run(150);
  h.target.armed = true;  // ...and the vehicle arms meanwhile
  const std::size_t before = h.times_of<mavlink::ParamSet>().size();
  h.run(5000);
  EXPECT_EQ(h.times_of<mavlink::ParamSet>().size(), before);
  EXPECT_EQ(h.line("EKF2_HGT_REF")->apply, ApplyState::failed);
  EXPECT_EQ(h.line("EKF2_HGT_REF")->apply_note, "stopped: the vehicle armed");
}

TEST(VehicleSetup, MalformedParamValuesAreCountedAndIgnored) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  mavlink::ParamValue bad = h.vehicle.value("EKF2_HGT_REF");
  bad.param_type = 42;  // no such MAV_PARAM_TYPE
  h.feed(bad);
  mavlink::ParamValue nan = h.vehicle.value("EKF2_EV_DELAY");
  nan.param_value = std::numeric_limits<float>::quiet_NaN();
  h.feed(nan);
  const auto snap = h.setup.snapshot();
  EXPECT_EQ(snap.counters.malformed, 2U);
  EXPECT_EQ(h.line("EKF2_HGT_REF")->item.current, 0.0);
  EXPECT_EQ(h.line("EKF2_EV_DELAY")->item.current, 0.0);
}

TEST(VehicleSetup, AGroundStationsChangeIsFollowed) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  h.vehicle.params["EKF2_EV_CTRL"].first = 15;
  h.feed(h.vehicle.value("EKF2_EV_CTRL"));
  EXPECT_EQ(h.line("EKF2_EV_CTRL")->item.status, SetupStatus::ok);
  EXPECT_NE(h.notes.back().find("changed from 0 to 15"), std::string::npos) << h.notes.back();
}

TEST(VehicleSetup, StatusTextKeepsTheLastFewAndLogsWarnings) {
  Harness h;
  for (int i = 0; i < 12; ++i) {
    mavlink::Statustext t;
    const std::string text = i == 11 ? "PreArm: VisOdom: not healthy" : "info " + std::to_string(i);
    std::memcpy(t.text.data(), text.data(), text.size());
    t.severity = i == 11 ? 3 : 6;
    h.feed(t);
  }
  const auto snap = h.setup.snapshot();
  ASSERT_EQ(snap.statustext.size(), kStatusTextKeep);
  EXPECT_EQ(snap.statustext.back().text, "PreArm: VisOdom: not healthy");
  EXPECT_EQ(severity_name(snap.statustext.back().severity), "error");
  ASSERT_EQ(h.notes.size(), 1U);
  EXPECT_EQ(h.notes[0], "vehicle says (error): PreArm: VisOdom: not healthy");
}

TEST(VehicleSetup, EstimatorFlagsInWords) {
  const EstimatorHealth ekf = describe_ekf_status(1 | 2 | 4 | 128);
  EXPECT_EQ(ekf.source, "EKF_STATUS_REPORT");
  EXPECT_NE(std::find(ekf.good.begin(), ekf.good.end(), "attitude"), ekf.good.end());
  EXPECT_NE(std::find(ekf.problems.begin(), ekf.problems.end(), "no horizontal position"),
            ekf.problems.end());
  EXPECT_NE(std::find(ekf.problems.begin(), ekf.problems.end(),
                      "constant position mode (no position source)"),
            ekf.problems.end());
  // 1024 differs: ArduPilot "not initialised", PX4 "GPS glitch".
  const auto e1024 = describe_ekf_status(1024).problems;
  EXPECT_NE(std::find(e1024.begin(), e1024.end(), "not initialised"), e1024.end());
  const auto p1024 = describe_estimator_status(1024).problems;
  EXPECT_NE(std::find(p1024.begin(), p1024.end(), "GPS glitch"), p1024.end());
  EXPECT_NE(std::find(p1024.begin(), p1024.end(), "no attitude"), p1024.end());
  // PX4 with vision yaw in a local frame never flags its attitude while it has a position (seen
  // in PX4 1.14.3 SITL flying on mocaplink): said, not a problem.
  const EstimatorHealth px4 = describe_estimator_status(2 | 4 | 8 | 16 | 32);
  EXPECT_TRUE(std::find(px4.problems.begin(), px4.problems.end(), "no attitude") ==
              px4.problems.end());
  EXPECT_EQ(px4.good.front(), "attitude (not flagged: a mocap heading is not aligned to north)");
}

TEST(VehicleSetup, DelayRecommendation) {
  Harness h;
  px4_defaults(h.vehicle);
  h.setup = VehicleSetup(kSysid, kOurCompid, Profile::ardupilot, MessageSet{MessageKind::odometry});
  h.vehicle.px4 = false;
  h.vehicle.version = 0x04060000u;
  h.target.autopilot = kMavAutopilotArdupilot;
  h.vehicle.params = {{"VISO_DELAY_MS", {10, kInt16}}};
  h.delay.capture_age_ms = 31.0;
  h.delay.link_rtt_ms = 8.0;
  h.run(40000);  // the other eight parameters are missing: 3 tries each before VISO_DELAY_MS
  const auto snap = h.setup.snapshot();
  EXPECT_EQ(snap.delay.parameter, "VISO_DELAY_MS");
  EXPECT_EQ(snap.delay.measured_ms, 35.0);
  EXPECT_EQ(snap.delay.recommended_ms, 35.0);
  EXPECT_EQ(snap.delay.current_ms, 10.0);
  EXPECT_EQ(h.line("VISO_DELAY_MS")->item.fix, 35.0);

  // PX4 with TIMESYNC over a fast link translates capture times itself: 0 is right.
  Harness p;
  px4_defaults(p.vehicle);
  p.delay = {31.0, 2.0, true};
  p.run(3000);
  EXPECT_EQ(p.setup.snapshot().delay.recommended_ms, 0.0);
  EXPECT_EQ(p.line("EKF2_EV_DELAY")->item.status, SetupStatus::ok);
  // Without it (a slow link), the whole delay.
  p.delay = {31.0, 40.0, true};
  p.run(200);
  EXPECT_EQ(p.setup.snapshot().delay.recommended_ms, 51.0);
}

TEST(VehicleSetup, ComingBackAfterSilenceReadsAgain) {
  Harness h;
  px4_defaults(h.vehicle);
  h.run(3000);
  const std::size_t first = h.times_of<mavlink::ParamRequestRead>().size();
  h.target.alive = false;
  h.run(5000);
  h.target.alive = true;
  h.run(3000);
  EXPECT_EQ(h.times_of<mavlink::ParamRequestRead>().size(), 2 * first);
}

// PX4 over uXRCE-DDS (issue 47): the link carries no parameters. Nothing is asked or written;
// the list is the newest firmware's, every item unread, and the state says why.
TEST(VehicleSetup, OverDdsNothingIsAskedAndTheListIsUnavailable) {
  Harness h;
  px4_defaults(h.vehicle);
  h.setup = VehicleSetup(kSysid, kOurCompid, Profile::px4, MessageSet{MessageKind::odometry},
                         VehicleLink::px4_dds);
  h.delay.capture_age_ms = 3.0;
  h.delay.dds_time_sync = true;
  h.run(30000);
  EXPECT_TRUE(h.sent.empty());
  const auto snap = h.setup.snapshot();
  EXPECT_EQ(snap.state, SetupState::unavailable);
  EXPECT_EQ(to_string(snap.state), "unavailable");
  ASSERT_FALSE(snap.lines.empty());
  for (const SetupLine& l : snap.lines) {
    EXPECT_EQ(l.item.status, SetupStatus::unread) << l.item.parameter;
  }
  ASSERT_NE(h.line("EKF2_EV_CTRL"), nullptr);  // 1.14's names: the newest rules
  // PX4's client converts timestamp_sample itself: 0, said with its condition.
  EXPECT_EQ(snap.delay.recommended_ms, 0.0);
  EXPECT_NE(snap.delay.basis.find("uXRCE-DDS time sync"), std::string::npos) << snap.delay.basis;
  EXPECT_EQ(snap.delay.basis.find("not measured yet"), std::string::npos) << snap.delay.basis;
  // While the link sends stamps of 0 (PX4's sync not right), PX4 stamps on arrival: the whole
  // delay.
  Harness a;
  a.setup = VehicleSetup(kSysid, kOurCompid, Profile::px4, MessageSet{MessageKind::odometry},
                         VehicleLink::px4_dds);
  a.delay.capture_age_ms = 3.0;
  a.run(2000);
  EXPECT_EQ(a.setup.snapshot().delay.recommended_ms, 3.0);
  EXPECT_NE(a.setup.snapshot().delay.basis.find("PX4 stamps these poses on arrival"),
            std::string::npos)
      << a.setup.snapshot().delay.basis;
  // Logged once, with where to check it instead.
  EXPECT_EQ(
      std::count_if(h.notes.begin(), h.notes.end(),
                    [](const std::string& n) { return n.rfind("set-up unavailable", 0) == 0; }),
      1);
  EXPECT_NE(std::string(unavailable_reason(VehicleLink::px4_dds)).find("MAVLink link"),
            std::string::npos);
  EXPECT_EQ(unavailable_reason(VehicleLink::mavlink), "");
  // Apply and reboot are refused, and nothing goes out for them.
  const std::vector<std::string> names{"EKF2_EV_CTRL"};
  EXPECT_FALSE(h.setup.apply(names, at_ms(h.now_ms)).accepted);
  std::vector<mavlink::Message> out;
  const SetupRequestResult reboot = h.setup.reboot(at_ms(h.now_ms), out);
  EXPECT_FALSE(reboot.accepted);
  EXPECT_NE(reboot.message.find("uXRCE-DDS"), std::string::npos);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace mocaplink::core

// The set-up rules (issue 28): each rule with a value that passes and one that fails, written from
// protocols/autopilots.md §8 and §12 (and the parameter docs it cites), not from the rule table:
// the expectations below are the documented facts, the table is what is checked.
#include "mocaplink/core/setup_rules.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mocaplink::core {
namespace {

struct Case {
  AutopilotFamily autopilot;
  SetupInput input;
  std::optional<FirmwareVersion> version;
  std::string parameter;
  double passes;
  double fails;
  SetupSeverity severity;       ///< of the failing value
  std::optional<double> fixed;  ///< what Apply writes for the failing value
};

constexpr FirmwareVersion kPx4_114{1, 14, 3, 255};
constexpr FirmwareVersion kPx4_113{1, 13, 2, 255};
constexpr FirmwareVersion kArdu45{4, 5, 7, 255};
constexpr FirmwareVersion kArdu46{4, 6, 0, 255};
constexpr auto kPx4 = AutopilotFamily::px4;
constexpr auto kArdu = AutopilotFamily::ardupilot;
constexpr auto kVision = SetupInput::vision;
constexpr auto kGps = SetupInput::fake_gps;
constexpr auto kBlocks = SetupSeverity::blocks;
constexpr auto kDegrades = SetupSeverity::degrades;
constexpr auto kAdvice = SetupSeverity::advice;

const std::vector<Case> kCases{
    // §12.1: EKF2_EV_CTRL 15 (11 without velocity); bit 1 is horizontal position.
    {kPx4, kVision, kPx4_114, "EKF2_EV_CTRL", 15, 0, kBlocks, 15},
    {kPx4, kVision, kPx4_114, "EKF2_EV_CTRL", 15, 1, kDegrades, 15},
    {kPx4, kVision, kPx4_114, "EKF2_HGT_REF", 3, 0, kDegrades, 3},
    {kPx4, kVision, kPx4_114, "EKF2_GPS_CTRL", 0, 7, kAdvice, 0},
    {kPx4, kVision, kPx4_114, "EKF2_MAG_TYPE", 5, 0, kAdvice, 5},
    // ≤ 1.13: EKF2_AID_MASK 24 (+256 for velocity), EKF2_HGT_MODE 3. Bit 1 (GPS) is kept.
    {kPx4, kVision, kPx4_113, "EKF2_AID_MASK", 280, 1, kBlocks, 281},
    {kPx4, kVision, kPx4_113, "EKF2_AID_MASK", 281, 9, kDegrades, 281},
    {kPx4, kVision, kPx4_113, "EKF2_HGT_MODE", 3, 0, kDegrades, 3},
    // §12.3: MAV_USEHILGPS 1, EKF2_GPS_CTRL 7.
    {kPx4, kGps, kPx4_114, "MAV_USEHILGPS", 1, 0, kBlocks, 1},
    {kPx4, kGps, kPx4_114, "EKF2_GPS_CTRL", 7, 0, kBlocks, 7},
    {kPx4, kGps, kPx4_113, "EKF2_AID_MASK", 1, 24, kBlocks, 25},
    // §12.2: VISO_TYPE 1, EK3_SRC1_POSXY/VELXY/POSZ/VELZ/YAW 6, GPS1_TYPE 0, EKF3.
    {kArdu, kVision, kArdu46, "AHRS_EKF_TYPE", 3, 2, kBlocks, 3},
    {kArdu, kVision, kArdu46, "VISO_TYPE", 1, 0, kBlocks, 1},
    {kArdu, kVision, kArdu46, "VISO_TYPE", 1, 3, kDegrades, 1},
    {kArdu, kVision, kArdu46, "EK3_SRC1_POSXY", 6, 3, kBlocks, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_VELXY", 0, 3, kDegrades, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_POSZ", 6, 1, kAdvice, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_POSZ", 6, 3, kDegrades, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_VELZ", 6, 3, kDegrades, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_YAW", 6, 1, kAdvice, 6},
    {kArdu, kVision, kArdu46, "EK3_SRC1_YAW", 6, 2, kBlocks, 6},
    {kArdu, kVision, kArdu46, "GPS1_TYPE", 0, 1, kAdvice, 0},
    {kArdu, kVision, kArdu45, "GPS_TYPE", 0, 1, kAdvice, 0},
    // §12.4: GPS1_TYPE 14, EK3_SRC1_POSXY 3, VELXY 3, POSZ 3 (or 1), YAW 2 or 3.
    {kArdu, kGps, kArdu46, "AHRS_EKF_TYPE", 3, 2, kBlocks, 3},
    {kArdu, kGps, kArdu46, "GPS1_TYPE", 14, 1, kBlocks, 14},
    {kArdu, kGps, kArdu45, "GPS_TYPE", 14, 0, kBlocks, 14},
    {kArdu, kGps, kArdu46, "EK3_SRC1_POSXY", 3, 6, kBlocks, 3},
    {kArdu, kGps, kArdu46, "EK3_SRC1_VELXY", 3, 6, kDegrades, 3},
    {kArdu, kGps, kArdu46, "EK3_SRC1_POSZ", 3, 1, kAdvice, 3},
    {kArdu, kGps, kArdu46, "EK3_SRC1_YAW", 3, 6, kBlocks, 2},
    {kArdu, kGps, kArdu46, "EK3_SRC1_YAW", 2, 1, kAdvice, 2},
};

const SetupRule* rule_named(const Case& c) {
  for (const SetupRule* r : rules_for(c.autopilot, c.version, c.input)) {
    if (r->parameter == c.parameter) return r;
  }
  return nullptr;
}

TEST(SetupRules, EachRulePassesItsValueAndFailsTheOther) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.parameter + " pass " + std::to_string(c.passes) + " fail " +
                 std::to_string(c.fails));
    const SetupRule* rule = rule_named(c);
    ASSERT_NE(rule, nullptr);
    const SetupItem ok = evaluate_rule(*rule, c.passes, false, std::nullopt);
    EXPECT_EQ(ok.status, SetupStatus::ok);
    EXPECT_FALSE(ok.fix);
    const SetupItem bad = evaluate_rule(*rule, c.fails, false, std::nullopt);
    EXPECT_EQ(bad.status, SetupStatus::wrong);
    EXPECT_EQ(bad.severity, c.severity);
    EXPECT_EQ(bad.fix, c.fixed);
    EXPECT_FALSE(bad.why.empty());
    EXPECT_FALSE(bad.needed.empty());
  }
}

TEST(SetupRules, EveryRuleHasACase) {
  // A rule without a documented case above is an untested rule.
  for (const SetupRule& r : setup_rules()) {
    if (r.fix.kind == SetupFix::Kind::measured_delay) continue;  // DelayRule tests
    const bool covered = std::any_of(kCases.begin(), kCases.end(), [&](const Case& c) {
      return c.autopilot == r.autopilot && c.input == r.input && c.parameter == r.parameter;
    });
    EXPECT_TRUE(covered) << r.parameter << " (" << to_string(r.autopilot) << ", "
                         << to_string(r.input) << ")";
  }
}

std::vector<std::string> names(AutopilotFamily a, std::optional<FirmwareVersion> v, SetupInput in) {
  std::vector<std::string> out;
  for (const SetupRule* r : rules_for(a, v, in)) out.emplace_back(r->parameter);
  return out;
}

bool has(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

TEST(SetupRules, RenamedParametersFollowTheVersion) {
  // PX4 1.14 replaced EKF2_AID_MASK/EKF2_HGT_MODE with EKF2_EV_CTRL, EKF2_GPS_CTRL, EKF2_HGT_REF.
  const auto px4_114 = names(kPx4, kPx4_114, kVision);
  EXPECT_TRUE(has(px4_114, "EKF2_EV_CTRL"));
  EXPECT_TRUE(has(px4_114, "EKF2_HGT_REF"));
  EXPECT_FALSE(has(px4_114, "EKF2_AID_MASK"));
  const auto px4_113 = names(kPx4, kPx4_113, kVision);
  EXPECT_TRUE(has(px4_113, "EKF2_AID_MASK"));
  EXPECT_TRUE(has(px4_113, "EKF2_HGT_MODE"));
  EXPECT_FALSE(has(px4_113, "EKF2_EV_CTRL"));
  // ArduPilot 4.6 renamed GPS_TYPE to GPS1_TYPE (and GPS_DELAY_MS to GPS1_DELAY_MS).
  EXPECT_TRUE(has(names(kArdu, kArdu46, kGps), "GPS1_TYPE"));
  EXPECT_TRUE(has(names(kArdu, kArdu46, kGps), "GPS1_DELAY_MS"));
  EXPECT_TRUE(has(names(kArdu, kArdu45, kGps), "GPS_TYPE"));
  EXPECT_FALSE(has(names(kArdu, kArdu45, kGps), "GPS1_TYPE"));
  // Unknown version: the newest names.
  EXPECT_EQ(names(kPx4, std::nullopt, kVision), px4_114);
  EXPECT_TRUE(has(names(kArdu, std::nullopt, kGps), "GPS1_TYPE"));
  // No rules for another autopilot or no input.
  EXPECT_TRUE(names(AutopilotFamily::other, kPx4_114, kVision).empty());
  EXPECT_TRUE(names(kPx4, kPx4_114, SetupInput::none).empty());
}

TEST(SetupRules, RebootFlagsFollowTheParameterDocs) {
  // PX4: EKF2_HGT_REF, EKF2_MAG_TYPE, EKF2_EV_DELAY need a reboot, EKF2_EV_CTRL does not;
  // ArduPilot: VISO_TYPE and GPS1_TYPE are @RebootRequired.
  const auto reboot = [](AutopilotFamily a, FirmwareVersion v, SetupInput in, std::string name) {
    for (const SetupRule* r : rules_for(a, v, in)) {
      if (r->parameter == name) return r->reboot;
    }
    ADD_FAILURE() << name;
    return false;
  };
  EXPECT_FALSE(reboot(kPx4, kPx4_114, kVision, "EKF2_EV_CTRL"));
  EXPECT_TRUE(reboot(kPx4, kPx4_114, kVision, "EKF2_HGT_REF"));
  EXPECT_TRUE(reboot(kPx4, kPx4_114, kVision, "EKF2_EV_DELAY"));
  EXPECT_FALSE(reboot(kPx4, kPx4_114, kGps, "MAV_USEHILGPS"));
  EXPECT_TRUE(reboot(kArdu, kArdu46, kVision, "VISO_TYPE"));
  EXPECT_TRUE(reboot(kArdu, kArdu46, kGps, "GPS1_TYPE"));
}

TEST(SetupRules, UnreadAndMissing) {
  const SetupRule* rule = rule_named(kCases.front());
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(evaluate_rule(*rule, std::nullopt, false, std::nullopt).status, SetupStatus::unread);
  const SetupItem missing = evaluate_rule(*rule, std::nullopt, true, std::nullopt);
  EXPECT_EQ(missing.status, SetupStatus::missing);
  EXPECT_EQ(missing.severity, SetupSeverity::blocks);
  EXPECT_FALSE(missing.fix);
}

TEST(SetupRules, DelayRuleComparesWithTheMeasurement) {
  const SetupRule* viso = nullptr;
  for (const SetupRule* r : rules_for(kArdu, kArdu46, kVision)) {
    if (r->parameter == "VISO_DELAY_MS") viso = r;
  }
  ASSERT_NE(viso, nullptr);
  // Not measured: nothing to compare with, nothing to write.
  const SetupItem unmeasured = evaluate_rule(*viso, 10, false, std::nullopt);
  EXPECT_EQ(unmeasured.status, SetupStatus::unmeasured);
  EXPECT_FALSE(unmeasured.fix);
  // 40 ms measured: 10 (the default) is off by 30 > max(10, 25 % of 40) → wrong, fix 40.
  const SetupItem off = evaluate_rule(*viso, 10, false, 40.4);
  EXPECT_EQ(off.status, SetupStatus::wrong);
  EXPECT_EQ(off.fix, 40.0);
  EXPECT_EQ(off.severity, SetupSeverity::advice);
  EXPECT_EQ(off.needed, "40 ms (measured)");
  EXPECT_EQ(evaluate_rule(*viso, 35, false, 40).status, SetupStatus::ok);
  // Clamped to the parameter's range (VISO_DELAY_MS 0–250).
  EXPECT_EQ(evaluate_rule(*viso, 10, false, 400).fix, 250.0);
}

TEST(SetupRules, FirmwareVersion) {
  // AUTOPILOT_VERSION.flight_sw_version = major << 24 | minor << 16 | patch << 8 | type.
  const auto v = decode_flight_sw_version(0x010E03FFu);
  ASSERT_TRUE(v);
  EXPECT_EQ(to_string(*v), "1.14.3");
  EXPECT_EQ(to_string(*decode_flight_sw_version(0x04070000u)), "4.7.0-dev");
  EXPECT_EQ(to_string(*decode_flight_sw_version(0x040500C0u)), "4.5.0-rc");
  EXPECT_FALSE(decode_flight_sw_version(0));
  EXPECT_TRUE(v->at_least(1, 14));
  EXPECT_FALSE(v->at_least(1, 15));
  EXPECT_TRUE(v->at_least(0, 99));
}

TEST(SetupRules, TheOriginGoesToAHeardVehicleAndToAPx4OnlyFrom115) {
  constexpr FirmwareVersion kPx4_115{1, 15, 0, 255};
  const std::optional<FirmwareVersion> none;
  // Nothing before a heartbeat, whatever it is.
  EXPECT_EQ(origin_gate(false, AutopilotFamily::ardupilot, kArdu46, true), OriginGate::wait);
  EXPECT_EQ(origin_gate(false, AutopilotFamily::px4, kPx4_115, true), OriginGate::wait);
  // ArduPilot and others: once heard, version or not.
  EXPECT_EQ(origin_gate(true, AutopilotFamily::ardupilot, none, false), OriginGate::send);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::unknown, none, false), OriginGate::send);
  // PX4: wait for its version; 1.15 and later get it, 1.14 and a silent one never.
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, none, false), OriginGate::wait);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, kPx4_115, true), OriginGate::send);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, FirmwareVersion{2, 0, 0, 255}, true),
            OriginGate::send);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, kPx4_114, true), OriginGate::withhold);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, kPx4_113, true), OriginGate::withhold);
  EXPECT_EQ(origin_gate(true, AutopilotFamily::px4, none, true), OriginGate::withhold);
  EXPECT_NE(withheld_origin_advice(kPx4_114).find("PX4 1.14.3 is not sent the origin"),
            std::string::npos);
  EXPECT_NE(withheld_origin_advice(none).find("profile px4-gps"), std::string::npos);
}

TEST(SetupRules, InputAndProfileMismatch) {
  const MessageSet odometry{MessageKind::odometry};
  const MessageSet hil{MessageKind::hil_gps};
  const MessageSet gps_input{MessageKind::gps_input};
  const MessageSet mocap{MessageKind::att_pos_mocap};
  EXPECT_EQ(setup_input(kPx4, odometry), SetupInput::vision);
  EXPECT_EQ(setup_input(kPx4, hil), SetupInput::fake_gps);
  EXPECT_EQ(setup_input(kPx4, mocap), SetupInput::none);  // EKF2 ignores ATT_POS_MOCAP (§1)
  EXPECT_EQ(setup_input(kArdu, mocap), SetupInput::vision);
  EXPECT_EQ(setup_input(kArdu, gps_input), SetupInput::fake_gps);
  EXPECT_EQ(setup_input(kPx4, gps_input), SetupInput::none);  // no GPS_INPUT handler on PX4

  EXPECT_FALSE(profile_item(Profile::px4, kPx4, SetupInput::vision));
  const auto swapped = profile_item(Profile::px4, kArdu, SetupInput::vision);
  ASSERT_TRUE(swapped);
  EXPECT_EQ(swapped->severity, SetupSeverity::advice);  // the same ODOMETRY works for both
  const auto useless = profile_item(Profile::ardupilot_gps, kPx4, SetupInput::none);
  ASSERT_TRUE(useless);
  EXPECT_EQ(useless->severity, SetupSeverity::blocks);
  EXPECT_EQ(useless->needed, "px4 (or px4-gps)");
}

}  // namespace
}  // namespace mocaplink::core

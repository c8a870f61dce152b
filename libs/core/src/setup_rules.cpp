// The set-up rules (setup_rules.hpp): one row per parameter, from protocols/autopilots.md §8/§12.
#include "mocaplink/core/setup_rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace mocaplink::core {
namespace {

using AK = Acceptance::Kind;
using FK = SetupFix::Kind;
using Sev = SetupSeverity;
constexpr auto kPx4 = AutopilotFamily::px4;
constexpr auto kArdu = AutopilotFamily::ardupilot;
constexpr auto kVision = SetupInput::vision;
constexpr auto kGps = SetupInput::fake_gps;
constexpr FirmwareVersion kAny{0, 0, 0, 0};
constexpr FirmwareVersion kPx4_1_14{1, 14, 0, 0};
constexpr FirmwareVersion kArdu4_6{4, 6, 0, 0};

// Value lists the rules point into (spans of static storage).
constexpr std::array<double, 1> k0{0};
constexpr std::array<double, 1> k1{1};
constexpr std::array<double, 1> k3{3};
constexpr std::array<double, 1> k5{5};
constexpr std::array<double, 1> k6{6};
constexpr std::array<double, 1> k14{14};
constexpr std::array<double, 2> k6or0{6, 0};
constexpr std::array<double, 2> k3or0{3, 0};
constexpr std::array<double, 2> k2or3{2, 3};

constexpr Acceptance one_of(std::span<const double> values) {
  return {AK::one_of, values, 0};
}
constexpr Acceptance bits(std::uint32_t b) {
  return {AK::bits, {}, b};
}
constexpr Acceptance nothing() {
  return {};
}
constexpr SetupFix set_to(double v) {
  return {FK::value, v, 0};
}
constexpr SetupFix add_bits(std::uint32_t b) {
  return {FK::add_bits, 0, b};
}
constexpr SetupFix measured() {
  return {FK::measured_delay, 0, 0};
}

constexpr std::string_view kDelayWhy =
    "the estimator places each pose this long before it arrived; measured from capture to the "
    "vehicle (the mocap system's latency, mocaplink's, and half the link's round trip)";

// clang-format off
const std::array kRules{
    // ---- PX4, external vision (ODOMETRY), 1.14 and later (autopilots.md §8.1, §12.1) ----
    SetupRule{kPx4, kVision, kPx4_1_14, kAny, "EKF2_EV_CTRL", bits(15), bits(1), Sev::blocks,
              Sev::degrades, add_bits(15), "15 (horizontal and vertical position, velocity, yaw)",
              "EKF2 fuses external vision only for the bits set (values 1 horizontal position, 2 "
              "vertical position, 4 velocity, 8 yaw): without 1 it ignores the poses, without 2 and "
              "8 height and heading come from another sensor", false, 0, 0},
    SetupRule{kPx4, kVision, kPx4_1_14, kAny, "EKF2_HGT_REF", one_of(k3), nothing(), Sev::degrades,
              Sev::advice, set_to(3), "3 (vision)",
              "height from the barometer (0) drifts indoors and in prop wash, GPS (1) has none "
              "indoors; mocap height does not",
              true, 0, 0},
    SetupRule{kPx4, kVision, kPx4_1_14, kAny, "EKF2_GPS_CTRL", one_of(k0), nothing(), Sev::advice,
              Sev::advice, set_to(0), "0 (no GNSS fusion)",
              "a GNSS receiver indoors has no fix, or a wrong one, to mix with mocap", false, 0, 0},
    // ---- PX4 1.13 and earlier: one mask for every aid (bits 8 vision position, 16 vision yaw,
    // 256 vision velocity) and EKF2_HGT_MODE ----
    SetupRule{kPx4, kVision, kAny, kPx4_1_14, "EKF2_AID_MASK", bits(8 | 16 | 256), bits(8),
              Sev::blocks, Sev::degrades, add_bits(8 | 16 | 256),
              "bits 8, 16 and 256 set (vision position, yaw, velocity)",
              "EKF2 fuses external vision only for the bits set: without 8 it ignores the poses",
              true, 0, 0},
    SetupRule{kPx4, kVision, kAny, kPx4_1_14, "EKF2_HGT_MODE", one_of(k3), nothing(), Sev::degrades,
              Sev::advice, set_to(3), "3 (vision)",
              "height from the barometer (0) drifts indoors and in prop wash, GPS (1) has none "
              "indoors; mocap height does not",
              true, 0, 0},
    SetupRule{kPx4, kVision, kAny, kAny, "EKF2_MAG_TYPE", one_of(k5), nothing(), Sev::advice,
              Sev::advice, set_to(5), "5 (none)",
              "with vision yaw fused, the magnetometer (disturbed indoors) only fights it", true,
              0, 0},
    SetupRule{kPx4, kVision, kAny, kAny, "EKF2_EV_DELAY", nothing(), nothing(), Sev::advice,
              Sev::advice, measured(), "", kDelayWhy, true, 0, 300},
    // ---- PX4, fake GPS (HIL_GPS; autopilots.md §3.6, §12.3) ----
    SetupRule{kPx4, kGps, kAny, kAny, "MAV_USEHILGPS", one_of(k1), nothing(), Sev::blocks,
              Sev::blocks, set_to(1), "1",
              "PX4 takes HIL_GPS outside HIL mode only with this set (and from its own system id)",
              false, 0, 0},
    SetupRule{kPx4, kGps, kPx4_1_14, kAny, "EKF2_GPS_CTRL", bits(7), bits(1), Sev::blocks,
              Sev::degrades, add_bits(7), "7 (position, altitude, velocity)",
              "EKF2 fuses the GNSS data only for the bits set", false, 0, 0},
    SetupRule{kPx4, kGps, kAny, kPx4_1_14, "EKF2_AID_MASK", bits(1), nothing(), Sev::blocks,
              Sev::blocks, add_bits(1), "bit 1 set (GPS)",
              "EKF2 fuses GPS only with bit 1 of the mask", true, 0, 0},
    // ---- ArduPilot, external navigation (VisualOdom; autopilots.md §8.2, §12.2) ----
    SetupRule{kArdu, kVision, kAny, kAny, "AHRS_EKF_TYPE", one_of(k3), nothing(), Sev::blocks,
              Sev::blocks, set_to(3), "3 (EKF3)",
              "EKF3 is the estimator that fuses external navigation and fake GPS as set up here",
              false, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "VISO_TYPE", one_of(k1), one_of(k2or3), Sev::blocks,
              Sev::degrades, set_to(1), "1 (MAVLink)",
              "0 ignores every vision message; 2 and 3 are for VIO cameras (they re-align yaw and "
              "drop data after resets); 1 passes mocap poses unchanged",
              true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "EK3_SRC1_POSXY", one_of(k6), nothing(), Sev::blocks,
              Sev::blocks, set_to(6), "6 (ExternalNav)",
              "EKF3 takes horizontal position only from the source named here", true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "EK3_SRC1_VELXY", one_of(k6or0), nothing(), Sev::degrades,
              Sev::advice, set_to(6), "6 (ExternalNav) or 0",
              "a velocity source that is not there (GPS indoors) leaves EKF3 without velocity aiding",
              true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "EK3_SRC1_POSZ", one_of(k6), one_of(k1), Sev::degrades,
              Sev::advice, set_to(6), "6 (ExternalNav; 1 barometer works)",
              "height from the barometer drifts indoors and in prop wash; mocap height does not",
              true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "EK3_SRC1_VELZ", one_of(k6or0), nothing(), Sev::degrades,
              Sev::advice, set_to(6), "6 (ExternalNav) or 0",
              "a vertical velocity source that is not there leaves EKF3 without it", true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "EK3_SRC1_YAW", one_of(k6), one_of(k1), Sev::blocks,
              Sev::advice, set_to(6), "6 (ExternalNav; 1 compass works)",
              "yaw from GPS has nothing to use indoors; the compass is disturbed indoors", true, 0,
              0},
    SetupRule{kArdu, kVision, kArdu4_6, kAny, "GPS1_TYPE", one_of(k0), nothing(), Sev::advice,
              Sev::advice, set_to(0), "0 (none)",
              "a GPS without a fix indoors only adds pre-arm failures", true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kArdu4_6, "GPS_TYPE", one_of(k0), nothing(), Sev::advice,
              Sev::advice, set_to(0), "0 (none)",
              "a GPS without a fix indoors only adds pre-arm failures", true, 0, 0},
    SetupRule{kArdu, kVision, kAny, kAny, "VISO_DELAY_MS", nothing(), nothing(), Sev::advice,
              Sev::advice, measured(), "", kDelayWhy, true, 0, 250},
    // ---- ArduPilot, fake GPS (GPS_INPUT; autopilots.md §3.5, §12.4) ----
    SetupRule{kArdu, kGps, kAny, kAny, "AHRS_EKF_TYPE", one_of(k3), nothing(), Sev::blocks,
              Sev::blocks, set_to(3), "3 (EKF3)",
              "EKF3 is the estimator that fuses external navigation and fake GPS as set up here",
              false, 0, 0},
    SetupRule{kArdu, kGps, kArdu4_6, kAny, "GPS1_TYPE", one_of(k14), nothing(), Sev::blocks,
              Sev::blocks, set_to(14), "14 (MAVLink)",
              "the MAVLink GPS driver (14) is the only one that reads GPS_INPUT", true, 0, 0},
    SetupRule{kArdu, kGps, kAny, kArdu4_6, "GPS_TYPE", one_of(k14), nothing(), Sev::blocks,
              Sev::blocks, set_to(14), "14 (MAVLink)",
              "the MAVLink GPS driver (14) is the only one that reads GPS_INPUT", true, 0, 0},
    SetupRule{kArdu, kGps, kAny, kAny, "EK3_SRC1_POSXY", one_of(k3), nothing(), Sev::blocks,
              Sev::blocks, set_to(3), "3 (GPS)",
              "EKF3 takes horizontal position only from the source named here", false, 0, 0},
    SetupRule{kArdu, kGps, kAny, kAny, "EK3_SRC1_VELXY", one_of(k3or0), nothing(), Sev::degrades,
              Sev::advice, set_to(3), "3 (GPS) or 0",
              "a velocity source that is not there leaves EKF3 without velocity aiding", false, 0,
              0},
    SetupRule{kArdu, kGps, kAny, kAny, "EK3_SRC1_POSZ", one_of(k3), one_of(k1), Sev::degrades,
              Sev::advice, set_to(3), "3 (GPS; 1 barometer works)",
              "height from the barometer drifts indoors and in prop wash; mocap height does not",
              false, 0, 0},
    SetupRule{kArdu, kGps, kAny, kAny, "EK3_SRC1_YAW", one_of(k2or3), one_of(k1), Sev::blocks,
              Sev::advice, set_to(2), "2 (GPS yaw; 3 with compass fallback; 1 compass works)",
              "GPS_INPUT carries mocap yaw, used only with 2 or 3; the compass is disturbed indoors",
              false, 0, 0},
    SetupRule{kArdu, kGps, kArdu4_6, kAny, "GPS1_DELAY_MS", nothing(), nothing(), Sev::advice,
              Sev::advice, measured(), "", kDelayWhy, false, 0, 250},
    SetupRule{kArdu, kGps, kAny, kArdu4_6, "GPS_DELAY_MS", nothing(), nothing(), Sev::advice,
              Sev::advice, measured(), "", kDelayWhy, false, 0, 250},
};
// clang-format on

bool in_range(const SetupRule& rule, const std::optional<FirmwareVersion>& version) {
  const bool has_since = rule.since.major != 0 || rule.since.minor != 0;
  const bool has_before = rule.before.major != 0 || rule.before.minor != 0;
  if (!version) return !has_before;  // unknown: the newest rules
  if (has_since && !version->at_least(rule.since.major, rule.since.minor)) return false;
  if (has_before && version->at_least(rule.before.major, rule.before.minor)) return false;
  return true;
}

/// "PX4 1.14.3", or "PX4" and `unknown` when the version is not known. Built by appending: GCC
/// 12 warns (-Wrestrict, a false positive) about `"PX4" + std::string&&` in a Release build.
std::string px4_with_version(const std::optional<FirmwareVersion>& version,
                             std::string_view unknown) {
  std::string out = "PX4";
  if (version) {
    out += ' ';
    out += to_string(*version);
  } else {
    out += unknown;
  }
  return out;
}

}  // namespace

std::string format_value(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

AutopilotFamily autopilot_family(std::uint8_t mav_autopilot) {
  switch (mav_autopilot) {
    case 0:
      return AutopilotFamily::unknown;
    case 3:
      return AutopilotFamily::ardupilot;
    case 12:
      return AutopilotFamily::px4;
    default:
      return AutopilotFamily::other;
  }
}

std::string_view to_string(AutopilotFamily family) {
  switch (family) {
    case AutopilotFamily::unknown:
      return "unknown";
    case AutopilotFamily::px4:
      return "px4";
    case AutopilotFamily::ardupilot:
      return "ardupilot";
    case AutopilotFamily::other:
      return "other";
  }
  return "unknown";
}

std::optional<FirmwareVersion> decode_flight_sw_version(std::uint32_t value) {
  if (value == 0) return std::nullopt;
  return FirmwareVersion{static_cast<int>((value >> 24) & 0xFF),
                         static_cast<int>((value >> 16) & 0xFF),
                         static_cast<int>((value >> 8) & 0xFF), static_cast<std::uint8_t>(value)};
}

std::string to_string(const FirmwareVersion& version) {
  std::string text = std::to_string(version.major) + "." + std::to_string(version.minor) + "." +
                     std::to_string(version.patch);
  if (version.type < 64) return text + "-dev";
  if (version.type < 128) return text + "-alpha";
  if (version.type < 192) return text + "-beta";
  if (version.type < 255) return text + "-rc";
  return text;
}

std::string_view to_string(SetupSeverity severity) {
  switch (severity) {
    case SetupSeverity::blocks:
      return "blocks";
    case SetupSeverity::degrades:
      return "degrades";
    case SetupSeverity::advice:
      return "advice";
  }
  return "advice";
}

std::string_view to_string(SetupInput input) {
  switch (input) {
    case SetupInput::vision:
      return "vision";
    case SetupInput::fake_gps:
      return "fake GPS";
    case SetupInput::none:
      return "none";
  }
  return "none";
}

std::string_view to_string(SetupStatus status) {
  switch (status) {
    case SetupStatus::unread:
      return "unread";
    case SetupStatus::ok:
      return "ok";
    case SetupStatus::wrong:
      return "wrong";
    case SetupStatus::missing:
      return "missing";
    case SetupStatus::unmeasured:
      return "unmeasured";
  }
  return "unread";
}

SetupInput setup_input(AutopilotFamily autopilot, const MessageSet& messages) {
  if (autopilot == AutopilotFamily::px4) {
    // EKF2 ignores ATT_POS_MOCAP and has no VISION_SPEED_ESTIMATE handler (§1).
    if (messages.contains(MessageKind::odometry) ||
        messages.contains(MessageKind::vision_position_estimate)) {
      return SetupInput::vision;
    }
    return messages.contains(MessageKind::hil_gps) ? SetupInput::fake_gps : SetupInput::none;
  }
  if (autopilot == AutopilotFamily::ardupilot) {
    if (messages.has_vision()) return SetupInput::vision;
    return messages.contains(MessageKind::gps_input) ? SetupInput::fake_gps : SetupInput::none;
  }
  return SetupInput::none;
}

bool Acceptance::contains(double value) const {
  switch (kind) {
    case Kind::none:
      return false;
    case Kind::one_of:
      return std::find(values.begin(), values.end(), value) != values.end();
    case Kind::bits: {
      if (!std::isfinite(value) || value < 0 || value > 4294967295.0) return false;
      const auto v = static_cast<std::uint32_t>(value);
      return (v & bits) == bits;
    }
  }
  return false;
}

std::span<const SetupRule> setup_rules() {
  return kRules;
}

std::vector<const SetupRule*> rules_for(AutopilotFamily autopilot,
                                        const std::optional<FirmwareVersion>& version,
                                        SetupInput input) {
  std::vector<const SetupRule*> out;
  for (const SetupRule& rule : kRules) {
    if (rule.autopilot == autopilot && rule.input == input && in_range(rule, version)) {
      out.push_back(&rule);
    }
  }
  return out;
}

SetupItem evaluate_rule(const SetupRule& rule, std::optional<double> current, bool gave_up,
                        std::optional<double> recommended_delay_ms) {
  SetupItem item;
  item.parameter = std::string(rule.parameter);
  item.current = current;
  item.needed = std::string(rule.needed);
  item.severity = rule.severity;
  item.why = std::string(rule.why);
  item.reboot = rule.reboot;
  if (rule.fix.kind == SetupFix::Kind::measured_delay) {
    if (recommended_delay_ms) {
      const double r =
          std::clamp(std::round(*recommended_delay_ms), rule.min_value, rule.max_value);
      item.needed = format_value(r) + " ms (measured)";
      if (!current) {
        item.status = gave_up ? SetupStatus::missing : SetupStatus::unread;
        return item;
      }
      const double tolerance = std::max(10.0, 0.25 * r);
      if (std::abs(*current - r) <= tolerance) {
        item.status = SetupStatus::ok;
      } else {
        item.status = SetupStatus::wrong;
        item.fix = r;
      }
      return item;
    }
    item.needed = "not measured yet";
    item.status =
        current ? SetupStatus::unmeasured : (gave_up ? SetupStatus::missing : SetupStatus::unread);
    return item;
  }
  if (!current) {
    item.status = gave_up ? SetupStatus::missing : SetupStatus::unread;
    return item;
  }
  if (rule.ok.contains(*current)) {
    item.status = SetupStatus::ok;
    return item;
  }
  item.status = SetupStatus::wrong;
  if (rule.tolerated.contains(*current)) item.severity = rule.tolerated_severity;
  if (rule.fix.kind == SetupFix::Kind::add_bits) {
    const auto v = std::isfinite(*current) && *current >= 0 && *current <= 4294967295.0
                       ? static_cast<std::uint32_t>(*current)
                       : 0u;
    item.fix = static_cast<double>(v | rule.fix.bits);
  } else {
    item.fix = rule.fix.value;
  }
  return item;
}

std::optional<SetupItem> profile_item(Profile profile, AutopilotFamily autopilot,
                                      SetupInput input) {
  if (autopilot != AutopilotFamily::px4 && autopilot != AutopilotFamily::ardupilot) {
    return std::nullopt;
  }
  const bool px4 = autopilot == AutopilotFamily::px4;
  SetupItem item;
  item.parameter = "profile";
  item.status = SetupStatus::wrong;
  if (input == SetupInput::none) {
    item.severity = SetupSeverity::blocks;
    item.needed = px4 ? "px4 (or px4-gps)" : "ardupilot (or ardupilot-gps)";
    item.why = std::string("this vehicle runs ") + (px4 ? "PX4" : "ArduPilot") +
               ", which fuses none of the messages profile " + std::string(to_string(profile)) +
               " sends (autopilots.md §1)";
    return item;
  }
  if (profile == Profile::automatic) return std::nullopt;  // follows the autopilot
  const bool for_px4 = profile == Profile::px4 || profile == Profile::px4_gps;
  const bool for_ardupilot = profile == Profile::ardupilot || profile == Profile::ardupilot_gps;
  if ((px4 && for_ardupilot) || (!px4 && for_px4)) {
    // The vision profiles send the same ODOMETRY; only the checks and advice differ.
    item.severity = SetupSeverity::advice;
    item.needed = input == SetupInput::vision ? (px4 ? "px4" : "ardupilot")
                                              : (px4 ? "px4-gps" : "ardupilot-gps");
    item.why = std::string("profile ") + std::string(to_string(profile)) + " is meant for " +
               (px4 ? "ArduPilot" : "PX4") + "; this vehicle runs " + (px4 ? "PX4" : "ArduPilot");
    return item;
  }
  return std::nullopt;
}

std::string profile_in_effect(Profile profile, AutopilotFamily autopilot) {
  if (profile != Profile::automatic) return std::string(to_string(profile));
  if (autopilot == AutopilotFamily::px4) return "px4";
  if (autopilot == AutopilotFamily::ardupilot) return "ardupilot";
  return "auto";
}

std::string unconfirmed_origin_advice(AutopilotFamily autopilot,
                                      const std::optional<FirmwareVersion>& version) {
  if (autopilot == AutopilotFamily::px4 && (!version || !version->at_least(1, 15))) {
    std::string advice = px4_with_version(version, "");
    advice +=
        " takes the origin but, without GPS, neither uses nor reports it (PX4-Autopilot#17249, "
        "fixed in 1.15): local modes (Position, Offboard) fly, global ones (Mission, RTL) do "
        "not. Upgrade PX4 to 1.15 or later, or use profile px4-gps (fake GPS)";
    return advice;
  }
  if (autopilot == AutopilotFamily::px4) {
    return "PX4 never reported the origin back: check that the vehicle's MAV_SYS_ID is this "
           "vehicle's system_id (PX4 takes SET_GPS_GLOBAL_ORIGIN addressed to it only) and that "
           "this link's MAVLink mode streams GPS_GLOBAL_ORIGIN";
  }
  if (autopilot == AutopilotFamily::ardupilot) {
    return "ArduPilot never reported the origin back: EKF3 takes it only when its position "
           "source can use it (EK3_SRC1_POSXY = 6, see the set-up list) and only once per boot; "
           "fix the set-up, reboot the vehicle, and mocaplink sends it again";
  }
  return "the vehicle never reported the origin back (GPS_GLOBAL_ORIGIN): global modes may not "
         "work; local ones do not need it";
}

OriginGate origin_gate(bool heard, AutopilotFamily autopilot,
                       const std::optional<FirmwareVersion>& version, bool identified) {
  if (!heard) return OriginGate::wait;
  if (autopilot != AutopilotFamily::px4) return OriginGate::send;
  if (version && version->at_least(1, 15)) return OriginGate::send;
  return identified ? OriginGate::withhold : OriginGate::wait;
}

std::string withheld_origin_advice(const std::optional<FirmwareVersion>& version) {
  std::string advice = px4_with_version(version, " of unknown version");
  advice +=
      " is not sent the origin: before 1.15, PX4 without GPS shifts its height estimate by the "
      "origin's altitude when it takes one (32 m in PX4 1.14.3 SITL) and neither uses nor "
      "reports it otherwise (PX4-Autopilot#17249). Local modes (Position, Offboard) need no "
      "origin; for global ones (Mission, RTL) upgrade PX4 to 1.15 or later, or use profile "
      "px4-gps (fake GPS)";
  return advice;
}

}  // namespace mocaplink::core

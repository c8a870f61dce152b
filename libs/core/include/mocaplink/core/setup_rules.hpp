// What a vehicle's autopilot must be set to for it to fuse what its profile sends (issue 28): the
// rules, one row per parameter, per autopilot, firmware version range and kind of input, from
// protocols/autopilots.md §8 (parameters), §12 (per profile), §3.5/§3.6 (fake GPS) and §4 (delay).
// Pure data and pure functions; the VehicleSetup (vehicle_setup.hpp) reads the parameters and
// evaluates them with evaluate_rule().
//
// A rule says which values are fine (`ok`), which are tolerated with a milder severity
// (`tolerated`), and what Apply writes (`fix`). For bitmask parameters "fine" means the bits are
// set (other bits are left alone, and Apply only adds the missing bits).
//
// Severity: blocks (the vehicle will not fuse the input, or will not arm or hold position on
// it), degrades (it fuses it, worse: height from the barometer, yaw from the compass...), advice
// (a recommended value that costs nothing when left).
// Thread-safety: immutable tables and pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/core/profile.hpp"

namespace mocaplink::core {

/// Which autopilot a vehicle runs, from its HEARTBEAT's `autopilot` (MAV_AUTOPILOT).
enum class AutopilotFamily : std::uint8_t {
  unknown,    ///< no heartbeat yet, or MAV_AUTOPILOT_GENERIC (0)
  px4,        ///< MAV_AUTOPILOT_PX4 (12)
  ardupilot,  ///< MAV_AUTOPILOT_ARDUPILOTMEGA (3)
  other,      ///< any other autopilot: no rules
};
[[nodiscard]] AutopilotFamily autopilot_family(std::uint8_t mav_autopilot);
/// "unknown", "px4", "ardupilot", "other" (the API's spellings).
[[nodiscard]] std::string_view to_string(AutopilotFamily family);

/// AUTOPILOT_VERSION.flight_sw_version: major << 24 | minor << 16 | patch << 8 | type, where
/// type is FIRMWARE_VERSION_TYPE (0 dev, 64 alpha, 128 beta, 192 rc, 255 official).
struct FirmwareVersion {
  int major = 0;
  int minor = 0;
  int patch = 0;
  std::uint8_t type = 255;
  /// This version is major.minor or later (patch and type ignored).
  [[nodiscard]] bool at_least(int major_, int minor_) const {
    return major > major_ || (major == major_ && minor >= minor_);
  }
  friend bool operator==(const FirmwareVersion&, const FirmwareVersion&) = default;
};
/// nullopt for 0 (a vehicle that does not fill it in).
[[nodiscard]] std::optional<FirmwareVersion> decode_flight_sw_version(std::uint32_t value);
/// "1.14.3", "4.6.0-dev", "4.5.0-beta", "4.5.0-rc" (the type only when not official).
[[nodiscard]] std::string to_string(const FirmwareVersion& version);

enum class SetupSeverity : std::uint8_t { blocks, degrades, advice };
/// "blocks", "degrades", "advice" (the API's spellings).
[[nodiscard]] std::string_view to_string(SetupSeverity severity);

/// What the vehicle is fed, which decides the rules: external navigation (ODOMETRY and the other
/// vision messages) or a fake GPS (HIL_GPS on PX4, GPS_INPUT on ArduPilot).
enum class SetupInput : std::uint8_t { vision, fake_gps, none };
[[nodiscard]] std::string_view to_string(SetupInput input);

/// The input a vehicle with `profile` sending `messages` feeds an `autopilot`:
///   vision    a vision message this autopilot fuses (ODOMETRY or VISION_POSITION_ESTIMATE; on
///             ArduPilot also VISION_SPEED_ESTIMATE and ATT_POS_MOCAP) — px4, ardupilot, auto
///   fake_gps  HIL_GPS (PX4) or GPS_INPUT (ArduPilot) — px4-gps, ardupilot-gps, classic on PX4
///   none      nothing this autopilot fuses (the profile-mismatch item says so)
[[nodiscard]] SetupInput setup_input(AutopilotFamily autopilot, const MessageSet& messages);

/// A set of values a parameter may have: equal to one of `values`, or (bits) with all of
/// `bits` set.
struct Acceptance {
  enum class Kind : std::uint8_t { none, one_of, bits } kind = Kind::none;
  std::span<const double> values;
  std::uint32_t bits = 0;
  [[nodiscard]] bool contains(double value) const;
};

/// What Apply writes: a fixed value, the current value with `bits` added, or the measured delay.
struct SetupFix {
  enum class Kind : std::uint8_t { value, add_bits, measured_delay } kind = Kind::value;
  double value = 0;
  std::uint32_t bits = 0;
};

/// One parameter rule.
struct SetupRule {
  AutopilotFamily autopilot = AutopilotFamily::unknown;
  SetupInput input = SetupInput::vision;
  /// Firmware versions the rule applies to: [since, before) by major.minor; 0.0 = no bound.
  /// A vehicle whose version is unknown gets the rules of the newest versions (before = 0.0).
  FirmwareVersion since{0, 0, 0, 0};
  FirmwareVersion before{0, 0, 0, 0};
  std::string_view parameter;
  Acceptance ok;
  Acceptance tolerated;  ///< Kind::none: nothing is tolerated
  SetupSeverity severity = SetupSeverity::blocks;
  SetupSeverity tolerated_severity = SetupSeverity::advice;
  SetupFix fix;
  std::string_view needed;  ///< the needed value as the operator reads it ("15", "6 (or 0)")
  std::string_view why;     ///< one sentence
  bool reboot = false;      ///< takes effect after the vehicle reboots
  /// The delay rule's bounds (ms): the parameter's range on the autopilot.
  double min_value = 0;
  double max_value = 0;
};

/// Every rule, in the order the list shows them.
[[nodiscard]] std::span<const SetupRule> setup_rules();

/// The rules for one vehicle: its autopilot, its version (nullopt: unknown → the newest rules)
/// and its input.
[[nodiscard]] std::vector<const SetupRule*> rules_for(AutopilotFamily autopilot,
                                                      const std::optional<FirmwareVersion>& version,
                                                      SetupInput input);

/// How a parameter stands against its rule.
enum class SetupStatus : std::uint8_t {
  unread,      ///< not read yet
  ok,          ///< within `ok`
  wrong,       ///< outside `ok` (severity says how bad)
  missing,     ///< the vehicle did not answer for it after every attempt (no such parameter?)
  unmeasured,  ///< a delay rule before the delay is measured (nothing to compare with)
};
[[nodiscard]] std::string_view to_string(SetupStatus status);

/// One line of the check list.
struct SetupItem {
  std::string parameter;
  std::optional<double> current;  ///< as the vehicle reported it
  std::string needed;             ///< the operator's reading of the needed value
  SetupSeverity severity = SetupSeverity::advice;
  SetupStatus status = SetupStatus::unread;
  std::string why;
  std::optional<double> fix;  ///< what Apply would write (wrong items only)
  bool reboot = false;
};

/// Evaluates `rule` against the vehicle's `current` value (nullopt: unread, or `missing` when
/// `gave_up`). `recommended_delay_ms`: the measured delay for a measured_delay rule (nullopt:
/// not measured). A delay within max(10 ms, 25 %) of the recommendation is ok.
[[nodiscard]] SetupItem evaluate_rule(const SetupRule& rule, std::optional<double> current,
                                      bool gave_up, std::optional<double> recommended_delay_ms);

/// The profile whose rules apply: `profile`, except auto, which is px4 or ardupilot by the
/// autopilot ("auto" while it is not known).
[[nodiscard]] std::string profile_in_effect(Profile profile, AutopilotFamily autopilot);

/// A vehicle running `autopilot` with `profile`: the profile item, when the profile was chosen
/// for another autopilot ("px4-gps" on ArduPilot: HIL_GPS is compiled out from 4.6), or sends
/// nothing this autopilot fuses. nullopt when the profile suits it (auto always does).
[[nodiscard]] std::optional<SetupItem> profile_item(Profile profile, AutopilotFamily autopilot,
                                                    SetupInput input);

/// Why a vehicle never confirmed the origin mocaplink sent it for kOriginGiveUpAfter, and what to
/// do, for its autopilot and version (one sentence for the dashboard and the log). PX4 up to 1.14
/// stores an origin set without GPS but never marks it valid, so it neither uses nor reports it
/// (EKF2's setEkfGlobalOrigin leaves the origin "not initialised" until a GPS fix; the
/// GPS_GLOBAL_ORIGIN stream sends only a valid one; PX4-Autopilot#17249, fixed in 1.15).
[[nodiscard]] std::string unconfirmed_origin_advice(AutopilotFamily autopilot,
                                                    const std::optional<FirmwareVersion>& version);

/// Whether SET_GPS_GLOBAL_ORIGIN may go to a vehicle now.
enum class OriginGate : std::uint8_t {
  wait,      ///< not yet: no heartbeat heard, or a PX4 whose version is not known yet
  send,      ///< yes
  withhold,  ///< never this boot: a PX4 before 1.15 (or of a version it would not say)
};
/// PX4 before 1.15 without GPS shifts its height estimate by the origin's altitude when it takes
/// one (EKF2's setEkfGlobalOrigin resets the height by the altitude minus the previous origin's,
/// which is 0 when none was set): against PX4 1.14.3 SITL the estimate jumped 32.34 m (the
/// origin's altitude) and a 1 m Offboard hover climbed to 18.65 m. It neither uses nor reports
/// the origin otherwise (unconfirmed_origin_advice). So a PX4 is sent the origin only once its
/// AUTOPILOT_VERSION says 1.15 or later. `heard`: a heartbeat from the vehicle this session;
/// `identified`: its AUTOPILOT_VERSION answered or given up. Other autopilots: once heard.
[[nodiscard]] OriginGate origin_gate(bool heard, AutopilotFamily autopilot,
                                     const std::optional<FirmwareVersion>& version,
                                     bool identified);
/// Why the origin is withheld, and what to do (one sentence for the dashboard and the log).
[[nodiscard]] std::string withheld_origin_advice(const std::optional<FirmwareVersion>& version);

/// A parameter's value as the list and the log write it ("%g": 15, 0.5, 1e+06).
[[nodiscard]] std::string format_value(double v);

}  // namespace mocaplink::core

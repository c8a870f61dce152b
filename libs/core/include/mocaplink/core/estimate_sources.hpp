// Estimate sources: whether the vehicle's own yaw and horizontal position, which the agreement
// check compares with mocap, are an independent reference or mocaplink's own poses fed back
// (issue 48). Comparing mocap with itself proves nothing about the axes: ArduCopter fusing
// ExternalNav yaw (EK3_SRC1_YAW = 6) reports mocaplink's yaw back whatever `up` says, and on the
// ground its position is mocaplink's too, so a Y-up mistake on a Z-up Vicon "agreed".
//
// From the parameters the set-up list reads (setup_rules.cpp; protocols/autopilots.md §8):
//   ArduPilot  EK3_SRC1_YAW 6 (ExternalNav) → yaw from mocap; 2 or 3 (GPS yaw) on a fake-GPS
//              profile → from mocap (GPS_INPUT carries our yaw); anything else → independent.
//              EK3_SRC1_POSXY 6 → position from mocap; 3 (GPS) on a fake-GPS profile → from mocap.
//              Only source set 1 is read: a vehicle switched to set 2 or 3 (EK3_SRC_OPTIONS,
//              RCx_OPTION 90) is judged by set 1 (the set-up list reads only that one too).
//   PX4        EKF2_EV_CTRL (1.14 on) bit 3 (8) yaw, bit 0 (1) horizontal position → from mocap;
//              EKF2_AID_MASK (up to 1.13) bit 4 (16) vision yaw, bit 3 (8) vision position.
//              A fake-GPS profile (HIL_GPS) → position from mocap, yaw independent (HIL_GPS has
//              no yaw field: the heading is the magnetometer's).
// A parameter not read (yet, or never answered) leaves that quantity `unknown`: the check then
// never agrees on it (it says so), rather than guess.
//
// A second heading, for a vehicle whose yaw comes from mocap (issue 48): its magnetometer's
// field, tilt-compensated here with ATTITUDE's roll and pitch, plus the declination the vehicle
// is configured with — a magnetic heading of the vehicle's own, whatever its estimator fuses.
//   ArduPilot  RAW_IMU's xmag/ymag/zmag: 4.5's GCS_MAVLINK::send_raw_imu fills them with
//              Compass::get_field(0), the primary compass's corrected field (offsets, scale,
//              motor compensation) in the body frame, milligauss — read whenever COMPASS_ENABLE
//              is set, whether or not COMPASS_USE lets EKF3 or DCM use it for yaw (ArduPilot's
//              ExternalNav guides set COMPASS_USE = 0; AHRS2's DCM yaw is then the gyros'
//              alone, seen on SITL). Judged a heading only once calibrated, by ArduPilot's own
//              test (Compass::configured: COMPASS_OFS_X/Y/Z not all 0): an uncalibrated
//              compass on a vehicle is tens of degrees off and would name a wrong nose.
//              COMPASS_ENABLE = 0 or uncalibrated → `none`. Declination: COMPASS_DEC (rad).
//   PX4        HIGHRES_IMU (vehicle_magnetometer less EKF2's bias, body FRD, gauss; v1.14
//              streams/HIGHRES_IMU.hpp), published whenever SYS_HAS_MAG = 1 whatever EKF2 fuses.
//              SYS_HAS_MAG = 0 → `none`. Declination: EKF2_MAG_DECL (deg).
// A declination not read counts as 0 (a few degrees against the 45° allowed). Over uXRCE-DDS
// nothing is read: `none`. Pure.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mocaplink/core/setup_rules.hpp"

namespace mocaplink::core {

enum class EstimateSource : std::uint8_t {
  unknown,      ///< the deciding parameter is not known (not read yet, or not answered)
  independent,  ///< the vehicle's own sensors (compass, GPS of its own): a real check
  mocap,        ///< mocaplink's poses fed back: agreement proves nothing about the axes
  none,         ///< the vehicle has no such quantity of its own (`heading` only)
};
/// "unknown", "independent", "mocap", "none" (the API's spellings).
[[nodiscard]] std::string_view to_string(EstimateSource source);

/// The basis of every quantity before the vehicle's first HEARTBEAT: which autopilot it runs, so
/// which parameter says where the quantity comes from, is not known yet.
inline constexpr std::string_view kHeartbeatBasis = "HEARTBEAT";

/// Where one compared quantity comes from, and the parameter that says so ("EK3_SRC1_YAW = 6";
/// when unknown, the parameter waited for: "EK3_SRC1_YAW", or kHeartbeatBasis).
struct QuantitySource {
  EstimateSource source = EstimateSource::unknown;
  std::string basis;
  friend bool operator==(const QuantitySource&, const QuantitySource&) = default;
};

struct EstimateSources {
  QuantitySource yaw;
  QuantitySource position;
  /// A second heading to check mocap's yaw against when `yaw` comes from mocap: independent
  /// (the vehicle's calibrated magnetometer), none (no compass, or not calibrated), unknown (the
  /// deciding parameters not read yet). `none` with an empty basis when `yaw` is not from mocap:
  /// the yaw itself is then the heading.
  QuantitySource heading{EstimateSource::none, {}};
  /// Added to the magnetometer's heading (rad, east positive): the vehicle's configured
  /// declination (COMPASS_DEC, EKF2_MAG_DECL); 0 when not read or no heading is wanted.
  double declination_rad = 0.0;
  friend bool operator==(const EstimateSources&, const EstimateSources&) = default;
};

/// A parameter's value as the vehicle reported it (nullopt: not read or never answered).
using ParameterLookup = std::function<std::optional<double>(std::string_view name)>;

/// The sources for a vehicle running `autopilot` (version `version`, nullopt when unknown: the
/// newest rules) fed `input`, from its parameters. An autopilot without rules (other, unknown)
/// leaves both unknown, with an empty basis.
[[nodiscard]] EstimateSources estimate_sources(AutopilotFamily autopilot,
                                               const std::optional<FirmwareVersion>& version,
                                               SetupInput input, const ParameterLookup& parameter);

/// The vehicle's yaw is mocap's and it has a heading of its own to check it against (its
/// magnetometer): that heading is asked for and compared.
[[nodiscard]] bool checks_second_heading(const EstimateSources& sources);

/// The parameters the sources are decided by that the set-up list has no rule for, read with
/// it: ArduPilot's COMPASS_ENABLE, COMPASS_OFS_X/Y/Z and COMPASS_DEC, PX4's SYS_HAS_MAG and
/// EKF2_MAG_DECL (the second heading); none for others.
[[nodiscard]] std::span<const std::string_view> source_parameters(AutopilotFamily autopilot);

/// A PX4 fed over uXRCE-DDS (VehicleLink::px4_dds): its parameters cannot be read there, and
/// its vision topic exists to be fused, so both are taken to come from mocap — they can still
/// disagree, never agree (the basis says it is assumed).
[[nodiscard]] EstimateSources px4_dds_sources();

/// "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6)",
/// "yaw not checkable yet: EK3_SRC1_YAW not read from the vehicle", or nullopt when the
/// vehicle's yaw is independent. `what` is "yaw" or "position".
[[nodiscard]] std::optional<std::string> describe_unchecked(std::string_view what,
                                                            const QuantitySource& source);

/// Both, joined with "; " (yaw first); nullopt when both are independent: the sentence the log
/// and the dashboard's `agreement.reason` give for what the check did not measure. A yaw from
/// mocap with an independent second heading that was compared (`heading_compared`) is named as
/// compared with that heading only ("yaw compared with its compass only (its compass in RAW_IMU:
/// COMPASS_ENABLE = 1, calibrated), 45° allowed: the vehicle's yaw comes from mocap
/// (EK3_SRC1_YAW = 6)"); one not compared (not arrived) says so; without one the sentence says why
/// there is none.
[[nodiscard]] std::optional<std::string> describe_unchecked(const EstimateSources& sources,
                                                            bool heading_compared = true);

}  // namespace mocaplink::core

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
// never agrees on it (it says so), rather than guess. Pure.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "mocaplink/core/setup_rules.hpp"

namespace mocaplink::core {

enum class EstimateSource : std::uint8_t {
  unknown,      ///< the deciding parameter is not known (not read yet, or not answered)
  independent,  ///< the vehicle's own sensors (compass, GPS of its own): a real check
  mocap,        ///< mocaplink's poses fed back: agreement proves nothing about the axes
};
/// "unknown", "independent", "mocap" (the API's spellings).
[[nodiscard]] std::string_view to_string(EstimateSource source);

/// Where one compared quantity comes from, and the parameter that says so ("EK3_SRC1_YAW = 6";
/// when unknown, the parameter waited for: "EK3_SRC1_YAW").
struct QuantitySource {
  EstimateSource source = EstimateSource::unknown;
  std::string basis;
  friend bool operator==(const QuantitySource&, const QuantitySource&) = default;
};

struct EstimateSources {
  QuantitySource yaw;
  QuantitySource position;
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
/// and the dashboard's `agreement.reason` give for what the check did not measure.
[[nodiscard]] std::optional<std::string> describe_unchecked(const EstimateSources& sources);

}  // namespace mocaplink::core

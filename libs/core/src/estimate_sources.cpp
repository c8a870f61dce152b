// Estimate sources (estimate_sources.hpp): is the vehicle's yaw / position mocaplink's own?
#include "mocaplink/core/estimate_sources.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>

#include "mocaplink/core/axis_fix.hpp"

namespace mocaplink::core {
namespace {

constexpr double kExternalNav = 6;  // EK3_SRCn_*: 6 ExternalNav
constexpr double kGps = 3;          // EK3_SRCn_POSXY: 3 GPS
constexpr double kGpsYaw = 2;       // EK3_SRCn_YAW: 2 GPS, 3 GPS with compass fallback
constexpr double kGpsYawFallback = 3;

QuantitySource from_mocap(std::string_view parameter, double value) {
  return {EstimateSource::mocap, std::string(parameter) + " = " + format_value(value)};
}

QuantitySource independent(std::string_view parameter, double value) {
  return {EstimateSource::independent, std::string(parameter) + " = " + format_value(value)};
}

QuantitySource unknown(std::string_view parameter) {
  return {EstimateSource::unknown, std::string(parameter)};
}

constexpr std::array<std::string_view, 5> kArduCompass{
    "COMPASS_ENABLE", "COMPASS_OFS_X", "COMPASS_OFS_Y", "COMPASS_OFS_Z", "COMPASS_DEC"};
constexpr std::array<std::string_view, 2> kPx4Compass{"SYS_HAS_MAG", "EKF2_MAG_DECL"};

/// ArduPilot's compass as a heading (estimate_sources.hpp): the field in RAW_IMU, whether or not
/// its EKF or DCM uses it for yaw, once it is enabled and calibrated.
QuantitySource ardupilot_heading(const ParameterLookup& parameter) {
  const auto enabled = parameter("COMPASS_ENABLE");
  if (!enabled) return unknown("COMPASS_ENABLE");
  if (*enabled == 0) return {EstimateSource::none, "COMPASS_ENABLE = 0: no compass"};
  // ArduPilot's own test of a calibrated compass (Compass::configured): offsets not all zero.
  bool calibrated = false;
  for (const std::string_view name : std::span(kArduCompass).subspan(1, 3)) {
    const auto offset = parameter(name);
    if (!offset) return unknown(name);
    calibrated = calibrated || *offset != 0;
  }
  if (!calibrated) {
    return {EstimateSource::none,
            "COMPASS_OFS_X, _Y and _Z = 0: its compass is not calibrated, so its field is no "
            "heading"};
  }
  return {EstimateSource::independent, "its compass in RAW_IMU: COMPASS_ENABLE = 1, calibrated"};
}

bool has_bit(double value, unsigned bit) {
  return (static_cast<unsigned long long>(std::llround(value)) & bit) != 0;
}

EstimateSources ardupilot(SetupInput input, const ParameterLookup& parameter) {
  const bool fake_gps = input == SetupInput::fake_gps;
  EstimateSources s;
  if (const auto yaw = parameter("EK3_SRC1_YAW")) {
    const bool ours =
        *yaw == kExternalNav || (fake_gps && (*yaw == kGpsYaw || *yaw == kGpsYawFallback));
    s.yaw = ours ? from_mocap("EK3_SRC1_YAW", *yaw) : independent("EK3_SRC1_YAW", *yaw);
  } else {
    s.yaw = unknown("EK3_SRC1_YAW");
  }
  if (const auto pos = parameter("EK3_SRC1_POSXY")) {
    const bool ours = *pos == kExternalNav || (fake_gps && *pos == kGps);
    s.position = ours ? from_mocap("EK3_SRC1_POSXY", *pos) : independent("EK3_SRC1_POSXY", *pos);
  } else {
    s.position = unknown("EK3_SRC1_POSXY");
  }
  if (s.yaw.source == EstimateSource::mocap) {
    s.heading = ardupilot_heading(parameter);
    s.declination_rad = parameter("COMPASS_DEC").value_or(0.0);  // radians
  }
  if (s.yaw.source == EstimateSource::unknown) s.heading = unknown("EK3_SRC1_YAW");
  return s;
}

/// The magnetometer's heading (HIGHRES_IMU, tilt-compensated here) where PX4 has one.
QuantitySource px4_heading(const ParameterLookup& parameter) {
  const auto has_mag = parameter("SYS_HAS_MAG");
  if (!has_mag) return unknown("SYS_HAS_MAG");
  if (*has_mag == 0) return {EstimateSource::none, "SYS_HAS_MAG = 0: no magnetometer"};
  return {EstimateSource::independent, "the magnetometer in HIGHRES_IMU: SYS_HAS_MAG = 1"};
}

EstimateSources px4(const std::optional<FirmwareVersion>& version, SetupInput input,
                    const ParameterLookup& parameter) {
  EstimateSources s;
  // EKF2_EV_CTRL from 1.14 (bits 1 horizontal position, 8 yaw); EKF2_AID_MASK before (8 vision
  // position, 16 vision yaw): setup_rules.cpp reads the one of the version.
  const bool old = version && !version->at_least(1, 14);
  const std::string_view name = old ? "EKF2_AID_MASK" : "EKF2_EV_CTRL";
  const unsigned yaw_bit = old ? 16 : 8;
  const unsigned pos_bit = old ? 8 : 1;
  const std::optional<double> value = parameter(name);
  if (input == SetupInput::fake_gps) {
    // HIL_GPS is mocaplink's position; it has no yaw, so the heading is the magnetometer's.
    s.position = {EstimateSource::mocap, "profile px4-gps (HIL_GPS)"};
    s.yaw = {EstimateSource::independent, "HIL_GPS carries no yaw"};
    return s;
  }
  if (!value) return {unknown(name), unknown(name), unknown(name)};
  s.yaw = has_bit(*value, yaw_bit) ? from_mocap(name, *value) : independent(name, *value);
  s.position = has_bit(*value, pos_bit) ? from_mocap(name, *value) : independent(name, *value);
  if (s.yaw.source == EstimateSource::mocap) {
    s.heading = px4_heading(parameter);
    s.declination_rad = parameter("EKF2_MAG_DECL").value_or(0.0) * std::numbers::pi / 180.0;
  }
  return s;
}

}  // namespace

std::string_view to_string(EstimateSource source) {
  switch (source) {
    case EstimateSource::unknown:
      return "unknown";
    case EstimateSource::independent:
      return "independent";
    case EstimateSource::mocap:
      return "mocap";
    case EstimateSource::none:
      return "none";
  }
  return "unknown";
}

bool checks_second_heading(const EstimateSources& sources) {
  return sources.yaw.source == EstimateSource::mocap &&
         sources.heading.source == EstimateSource::independent;
}

std::span<const std::string_view> source_parameters(AutopilotFamily autopilot) {
  if (autopilot == AutopilotFamily::ardupilot) return kArduCompass;
  if (autopilot == AutopilotFamily::px4) return kPx4Compass;
  return {};
}

EstimateSources estimate_sources(AutopilotFamily autopilot,
                                 const std::optional<FirmwareVersion>& version, SetupInput input,
                                 const ParameterLookup& parameter) {
  switch (autopilot) {
    case AutopilotFamily::ardupilot:
      return ardupilot(input, parameter);
    case AutopilotFamily::px4:
      return px4(version, input, parameter);
    case AutopilotFamily::unknown: {
      const QuantitySource waiting{EstimateSource::unknown, std::string(kHeartbeatBasis)};
      return {waiting, waiting, waiting};
    }
    case AutopilotFamily::other:
      break;
  }
  return {};
}

EstimateSources px4_dds_sources() {
  const QuantitySource assumed{EstimateSource::mocap,
                               "assumed: PX4 fuses the poses it is sent over uXRCE-DDS, and "
                               "EKF2_EV_CTRL cannot be read there"};
  // Nothing but poses goes over uXRCE-DDS here: no magnetometer is read.
  return {assumed, assumed, {EstimateSource::none, "no MAVLink link to read its magnetometer"}};
}

std::optional<std::string> describe_unchecked(std::string_view what, const QuantitySource& source) {
  const std::string name(what);
  switch (source.source) {
    case EstimateSource::independent:
    case EstimateSource::none:
      return std::nullopt;
    case EstimateSource::mocap:
      return name + " not checkable: the vehicle's " + name + " comes from mocap (" + source.basis +
             ")";
    case EstimateSource::unknown:
      if (source.basis.empty()) {
        return name + " not checkable: unknown whether the vehicle's " + name +
               " comes from mocap (no set-up rules for its autopilot)";
      }
      if (source.basis == kHeartbeatBasis) {
        return name + " not checkable yet: no HEARTBEAT from the vehicle yet (which autopilot " +
               "says where its " + name + " comes from)";
      }
      return name + " not checkable yet: " + source.basis +
             " not read from the vehicle (does its " + name + " come from mocap?)";
  }
  return std::nullopt;
}

std::optional<std::string> describe_unchecked(const EstimateSources& sources,
                                              bool heading_compared) {
  const auto unheard = [](const QuantitySource& q) {
    return q.source == EstimateSource::unknown && q.basis == kHeartbeatBasis;
  };
  if (unheard(sources.yaw) && unheard(sources.position)) {
    return "yaw and position not checkable yet: no HEARTBEAT from the vehicle yet (which "
           "autopilot says where they come from)";
  }
  std::optional<std::string> yaw = describe_unchecked("yaw", sources.yaw);
  if (sources.yaw.source == EstimateSource::mocap) {
    const QuantitySource& h = sources.heading;
    char limit[16];
    std::snprintf(limit, sizeof limit, "%g", kMaxHeadingOffsetDeg);
    if (h.source == EstimateSource::independent && heading_compared) {
      yaw = "yaw compared with its compass only (" + h.basis + "), " + limit +
            "° allowed: the vehicle's yaw comes from mocap (" + sources.yaw.basis + ")";
    } else if (h.source == EstimateSource::independent) {
      *yaw += "; its compass heading (" + h.basis + ") has not arrived: the nose is unchecked";
    } else if (h.source == EstimateSource::none && !h.basis.empty()) {
      *yaw += ", and it has no heading of its own (" + h.basis + "): the nose is unchecked";
    } else if (h.source == EstimateSource::unknown) {
      *yaw += "; its own heading not known yet: " + h.basis + " not read from the vehicle";
    }
  }
  const auto position = describe_unchecked("position", sources.position);
  if (yaw && position) return *yaw + "; " + *position;
  return yaw ? yaw : position;
}

}  // namespace mocaplink::core

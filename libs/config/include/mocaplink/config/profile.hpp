// Message profiles and message kinds as the configuration names them (DESIGN.md "Message profiles",
// protocols/autopilots.md §12). Which messages a non-custom profile sends is decided by the core.
#pragma once

#include <string_view>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

/// `profile = "..."` of a [[vehicle]].
enum class Profile { px4, ardupilot, px4_gps, ardupilot_gps, classic, custom };

/// "px4", "ardupilot", "px4-gps", "ardupilot-gps", "classic", "custom".
[[nodiscard]] const char* to_string(Profile profile);
/// Parses the spellings above; the error names the closest one ("did you mean").
[[nodiscard]] ValueOrError<Profile> parse_profile(std::string_view text);

/// One entry of `messages = [...]` (profile "custom" only).
enum class MessageKind {
  odometry,                  ///< ODOMETRY (331)
  vision_position_estimate,  ///< VISION_POSITION_ESTIMATE (102)
  vision_speed_estimate,     ///< VISION_SPEED_ESTIMATE (103)
  att_pos_mocap,             ///< ATT_POS_MOCAP (138)
  hil_gps,                   ///< HIL_GPS (113); needs [origin]
  gps_input,                 ///< GPS_INPUT (232); needs [origin]
  local_position_ned,        ///< LOCAL_POSITION_NED (32)
};

/// "odometry", "vision_position_estimate", ... (the config spelling, lower snake case).
[[nodiscard]] const char* to_string(MessageKind kind);
/// Parses the spellings above; the error names the closest one.
[[nodiscard]] ValueOrError<MessageKind> parse_message_kind(std::string_view text);

/// True for the profiles and messages that put a geodetic position on the wire and so need the
/// [origin] table: px4-gps (HIL_GPS), ardupilot-gps (GPS_INPUT), classic (HIL_GPS).
[[nodiscard]] bool needs_origin(Profile profile);
[[nodiscard]] bool needs_origin(MessageKind kind);

}  // namespace mocaplink::config

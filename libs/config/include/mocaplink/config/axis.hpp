// Axis names used by the frame mapping keys: [mocap] up / north / body_forward / body_up and the
// per-vehicle body_forward / body_up overrides (docs/config.md, DESIGN.md "Conventions").
#pragma once

#include <string>
#include <string_view>
#include <variant>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

/// A signed coordinate axis of a right-handed frame, written "+x", "-x", "+y", "-y", "+z", "-z".
enum class Axis { pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };

/// "+x", "-x", ... (the spelling the config file uses).
[[nodiscard]] const char* to_string(Axis axis);
/// Parses "+x" ... "-z" (lower case; "x" without a sign is rejected to avoid guessing).
[[nodiscard]] ValueOrError<Axis> parse_axis(std::string_view text);
/// 0 for x, 1 for y, 2 for z.
[[nodiscard]] int axis_index(Axis axis);
/// +1 or -1.
[[nodiscard]] int axis_sign(Axis axis);
/// True when the two axes are at right angles (different coordinate, either sign).
[[nodiscard]] bool are_perpendicular(Axis a, Axis b);

/// North given as an angle in the horizontal plane of the mocap frame: north is the reference
/// axis rotated by `deg` degrees about the up axis (right-handed, i.e. counter-clockwise seen from
/// above). The reference axis is +x, or +y when up is ±x — the same rule as
/// core::WorldAxisMapping (libs/core/include/mocaplink/core/axis_mapping.hpp), which applies it.
/// So with up = "+z", "angle:0" is "+x" and "angle:90" is "+y". Valid range −360 ≤ deg ≤ 360.
struct NorthAngle {
  double deg = 0.0;
  friend bool operator==(const NorthAngle&, const NorthAngle&) = default;
};

/// The mocap direction that becomes NED north: a horizontal axis ("+x") or an angle ("angle:37.5").
using North = std::variant<Axis, NorthAngle>;

/// "+x" or "angle:37.5" (shortest round-trip decimal).
[[nodiscard]] std::string to_string(const North& north);
/// Parses an axis or "angle:DEG" (DEG a finite decimal in [-360, 360]).
[[nodiscard]] ValueOrError<North> parse_north(std::string_view text);

}  // namespace mocaplink::config

// Parsing the frame-mapping keys — [mocap] up / north / body_forward / body_up and the
// per-vehicle body_forward / body_up overrides (docs/config.md, DESIGN.md "Conventions") —
// straight into the core's axis types (mocaplink/core/axis_mapping.hpp: SignedAxis, North), with
// the configuration's error messages. The right-angle rule is the core's (core::are_perpendicular,
// checked again by WorldAxisMapping::make / BodyAxisMapping::make); the config reports it with
// file:line.
#pragma once

#include <string_view>

#include "mocaplink/config/value_or_error.hpp"
#include "mocaplink/core/axis_mapping.hpp"

namespace mocaplink::config {

/// Parses "+x" ... "-z" (lower case; "x" without a sign is rejected to avoid guessing).
[[nodiscard]] ValueOrError<core::SignedAxis> parse_axis(std::string_view text);
/// Parses an axis or "angle:DEG" (DEG a finite decimal in [-360, 360]).
[[nodiscard]] ValueOrError<core::North> parse_north(std::string_view text);

}  // namespace mocaplink::config

#include "mocaplink/config/axis.hpp"

#include <cmath>
#include <string>

#include "text_util.hpp"

namespace mocaplink::config {
namespace {

constexpr std::string_view kAnglePrefix = "angle:";

}  // namespace

ValueOrError<core::SignedAxis> parse_axis(std::string_view text) {
  const auto axis = core::parse_signed_axis(text, "");
  if (axis) return *axis;
  return ValueOrError<core::SignedAxis>::failure("expected one of +x, -x, +y, -y, +z, -z, got " +
                                                 detail::quoted(text));
}

ValueOrError<core::North> parse_north(std::string_view text) {
  if (text.substr(0, kAnglePrefix.size()) == kAnglePrefix) {
    const auto deg = detail::parse_double(text.substr(kAnglePrefix.size()));
    if (!deg || !std::isfinite(*deg) || *deg < -360.0 || *deg > 360.0) {
      return ValueOrError<core::North>::failure(
          "angle must be a number of degrees from -360 to 360, as in \"angle:37.5\", got " +
          detail::quoted(text));
    }
    return core::North{core::NorthAngle{*deg}};
  }
  auto axis = parse_axis(text);
  if (!axis) {
    return ValueOrError<core::North>::failure(
        "expected one of +x, -x, +y, -y, +z, -z or \"angle:DEG\", got " + detail::quoted(text));
  }
  return core::North{axis.value()};
}

}  // namespace mocaplink::config

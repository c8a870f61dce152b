#include "mocaplink/config/axis.hpp"

#include <array>
#include <cmath>
#include <string>

#include "text_util.hpp"

namespace mocaplink::config {
namespace {

constexpr std::array<std::string_view, 6> kAxisNames = {"+x", "-x", "+y", "-y", "+z", "-z"};
constexpr std::string_view kAnglePrefix = "angle:";

}  // namespace

const char* to_string(Axis axis) {
  switch (axis) {
    case Axis::pos_x:
      return "+x";
    case Axis::neg_x:
      return "-x";
    case Axis::pos_y:
      return "+y";
    case Axis::neg_y:
      return "-y";
    case Axis::pos_z:
      return "+z";
    case Axis::neg_z:
      return "-z";
  }
  return "?";
}

ValueOrError<Axis> parse_axis(std::string_view text) {
  for (std::size_t i = 0; i < kAxisNames.size(); ++i) {
    if (text == kAxisNames[i]) return static_cast<Axis>(i);
  }
  return ValueOrError<Axis>::failure("expected one of +x, -x, +y, -y, +z, -z, got " +
                                     detail::quoted(text));
}

int axis_index(Axis axis) {
  return static_cast<int>(axis) / 2;
}

int axis_sign(Axis axis) {
  return static_cast<int>(axis) % 2 == 0 ? 1 : -1;
}

bool are_perpendicular(Axis a, Axis b) {
  return axis_index(a) != axis_index(b);
}

std::string to_string(const North& north) {
  if (const auto* axis = std::get_if<Axis>(&north)) return to_string(*axis);
  return std::string(kAnglePrefix) + detail::format_number(std::get<NorthAngle>(north).deg);
}

ValueOrError<North> parse_north(std::string_view text) {
  if (text.substr(0, kAnglePrefix.size()) == kAnglePrefix) {
    const auto deg = detail::parse_double(text.substr(kAnglePrefix.size()));
    if (!deg || !std::isfinite(*deg) || *deg < -360.0 || *deg > 360.0) {
      return ValueOrError<North>::failure(
          "angle must be a number of degrees from -360 to 360, as in \"angle:37.5\", got " +
          detail::quoted(text));
    }
    return North{NorthAngle{*deg}};
  }
  auto axis = parse_axis(text);
  if (!axis) {
    return ValueOrError<North>::failure(
        "expected one of +x, -x, +y, -y, +z, -z or \"angle:DEG\", got " + detail::quoted(text));
  }
  return North{axis.value()};
}

}  // namespace mocaplink::config

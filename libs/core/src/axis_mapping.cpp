#include "mocaplink/core/axis_mapping.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <system_error>

namespace mocaplink::core {
namespace {

constexpr std::string_view kAnglePrefix = "angle:";

// Columns of a rotation built from three orthonormal unit vectors; as a quaternion with w >= 0.
Eigen::Quaterniond canonical_quaternion(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q;
}

AxisMappingError error(std::string_view field, std::string message) {
  return AxisMappingError{std::string(field), std::move(message)};
}

// "angle:DEG" -> degrees. std::from_chars for double is locale-independent.
AxisMappingResult<double> parse_angle(std::string_view text, std::string_view field) {
  const std::string_view number = text.substr(kAnglePrefix.size());
  double deg = 0.0;
  const char* first = number.data();
  const char* last = number.data() + number.size();
  if (!number.empty() && *first == '+') ++first;  // from_chars refuses a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, deg);
  if (number.empty() || ec != std::errc{} || ptr != last || !std::isfinite(deg)) {
    return error(field, "expected \"angle:DEG\" with a finite number of degrees, got \"" +
                            std::string(text) + "\"");
  }
  return deg;
}

}  // namespace

Eigen::Vector3d SignedAxis::unit() const {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v[index] = static_cast<double>(sign);
  return v;
}

AxisMappingResult<SignedAxis> parse_signed_axis(std::string_view text, std::string_view field) {
  if (text.size() == 2 && (text[0] == '+' || text[0] == '-') && text[1] >= 'x' && text[1] <= 'z') {
    return SignedAxis{text[1] - 'x', text[0] == '+' ? 1 : -1};
  }
  return error(field, "expected one of +x -x +y -y +z -z, got \"" + std::string(text) + "\"");
}

std::string to_string(const SignedAxis& axis) {
  std::string out(axis.sign > 0 ? "+" : "-");
  out.push_back(static_cast<char>('x' + axis.index));
  return out;
}

std::string to_string(const North& north) {
  if (const auto* axis = std::get_if<SignedAxis>(&north)) return to_string(*axis);
  std::array<char, 64> buffer{};
  const double deg = std::get<NorthAngle>(north).deg;
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), deg);
  return std::string(kAnglePrefix) + std::string(buffer.data(), result.ptr);
}

WorldAxisMapping::WorldAxisMapping(SignedAxis up, North north, const Eigen::Matrix3d& r_ned_world)
    : up_(up),
      north_(north),
      r_ned_world_(r_ned_world),
      q_ned_world_(canonical_quaternion(r_ned_world)) {}

AxisMappingResult<WorldAxisMapping> WorldAxisMapping::parse(std::string_view up,
                                                            std::string_view north) {
  const auto up_axis = parse_signed_axis(up, "up");
  if (!up_axis) return up_axis.error();
  if (north.starts_with(kAnglePrefix)) {
    const auto deg = parse_angle(north, "north");
    if (!deg) return deg.error();
    return make(*up_axis, NorthAngle{*deg});
  }
  const auto north_axis = parse_signed_axis(north, "north");
  if (!north_axis) {
    return error("north", "expected one of +x -x +y -y +z -z or \"angle:DEG\", got \"" +
                              std::string(north) + "\"");
  }
  return make(*up_axis, *north_axis);
}

AxisMappingResult<WorldAxisMapping> WorldAxisMapping::make(SignedAxis up, const North& north) {
  const Eigen::Vector3d up_w = up.unit();
  Eigen::Vector3d north_w;
  if (const auto* angle = std::get_if<NorthAngle>(&north)) {
    // Reference axis: +x, or +y when up is +-x (docs/frames.md "Axis mapping").
    const Eigen::Vector3d reference =
        up.index == 0 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const double rad = std::fmod(angle->deg, 360.0) * std::numbers::pi / 180.0;
    // Right-hand rotation of the (horizontal) reference about up.
    north_w = Eigen::AngleAxisd(rad, up_w) * reference;
  } else {
    const SignedAxis north_axis = std::get<SignedAxis>(north);
    if (!are_perpendicular(up, north_axis)) {
      return error("north", "north \"" + to_string(north_axis) + "\" is parallel to up \"" +
                                to_string(up) + "\"; it must be a horizontal axis");
    }
    north_w = north_axis.unit();
  }
  // NED: N x E = D, D = -up, so E = D x N.
  const Eigen::Vector3d down_w = -up_w;
  const Eigen::Vector3d east_w = down_w.cross(north_w);
  Eigen::Matrix3d r_ned_world;
  r_ned_world.row(0) = north_w.transpose();
  r_ned_world.row(1) = east_w.transpose();
  r_ned_world.row(2) = down_w.transpose();
  return WorldAxisMapping(up, north, r_ned_world);
}

BodyAxisMapping::BodyAxisMapping(SignedAxis forward, SignedAxis up,
                                 const Eigen::Matrix3d& r_body_frd)
    : forward_(forward),
      up_(up),
      r_body_frd_(r_body_frd),
      q_body_frd_(canonical_quaternion(r_body_frd)) {}

AxisMappingResult<BodyAxisMapping> BodyAxisMapping::parse(std::string_view forward,
                                                          std::string_view up) {
  const auto fwd_axis = parse_signed_axis(forward, "body_forward");
  if (!fwd_axis) return fwd_axis.error();
  const auto up_axis = parse_signed_axis(up, "body_up");
  if (!up_axis) return up_axis.error();
  return make(*fwd_axis, *up_axis);
}

AxisMappingResult<BodyAxisMapping> BodyAxisMapping::make(SignedAxis forward, SignedAxis up) {
  if (!are_perpendicular(forward, up)) {
    return error("body_up", "body_up \"" + to_string(up) + "\" is parallel to body_forward \"" +
                                to_string(forward) + "\"");
  }
  // FRD: F x R = D, D = -up, so R = D x F.
  const Eigen::Vector3d f_b = forward.unit();
  const Eigen::Vector3d d_b = -up.unit();
  const Eigen::Vector3d r_b = d_b.cross(f_b);
  Eigen::Matrix3d r_body_frd;
  r_body_frd.col(0) = f_b;
  r_body_frd.col(1) = r_b;
  r_body_frd.col(2) = d_b;
  return BodyAxisMapping(forward, up, r_body_frd);
}

AxisMappingResult<AxisMapping> AxisMapping::parse(std::string_view up, std::string_view north,
                                                  std::string_view body_forward,
                                                  std::string_view body_up) {
  const auto world = WorldAxisMapping::parse(up, north);
  if (!world) return world.error();
  const auto body = BodyAxisMapping::parse(body_forward, body_up);
  if (!body) return body.error();
  return AxisMapping(*world, *body);
}

Eigen::Quaterniond AxisMapping::attitude_ned_frd(const Eigen::Quaterniond& q_world_body) const {
  return world_.q_ned_world() * q_world_body * body_.q_body_frd();
}

}  // namespace mocaplink::core

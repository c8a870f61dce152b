#include "mocaplink/wire/qtm_frame.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "mocaplink/wire/vicon_pose.hpp"

namespace mocaplink::wire::qtm {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

const SixDof* pick(const DataPacket& data, Component preferred) {
  for (const SixDof& c : data.six_dof) {
    if (c.type == preferred) return &c;
  }
  return data.six_dof.empty() ? nullptr : &data.six_dof.front();
}

bool all_nan(const Body6d& b, bool matrix) {
  const auto nan = [](float f) { return std::isnan(f); };
  return std::all_of(b.position_mm.begin(), b.position_mm.end(), nan) &&
         (matrix ? std::all_of(b.rotation.begin(), b.rotation.end(), nan)
                 : std::all_of(b.euler_deg.begin(), b.euler_deg.end(), nan));
}

/// The matrix column by column on the wire → the row-major layout the shared rotation check reads.
std::array<double, 9> row_major(const Body6d& b) {
  std::array<double, 9> out{};
  for (std::size_t row = 0; row < 3; ++row) {
    for (std::size_t col = 0; col < 3; ++col) out[row * 3 + col] = b.rotation[col * 3 + row];
  }
  return out;
}

std::optional<Eigen::Quaterniond> orientation(const Body6d& b, bool matrix) {
  if (!matrix) {
    const std::array<double, 3> deg{b.euler_deg[0], b.euler_deg[1], b.euler_deg[2]};
    if (!std::all_of(deg.begin(), deg.end(), [](double d) { return std::isfinite(d); })) {
      return std::nullopt;
    }
    return quaternion_from_euler(deg);
  }
  return vicon::quaternion_from_rotation(row_major(b));
}

}  // namespace

Result<MappedFrame> to_mocap_frame(const DataPacket& data, Component preferred,
                                   std::span<const BodyParameters> bodies,
                                   std::optional<double> frequency_hz) {
  const SixDof* component = pick(data, preferred);
  if (component == nullptr) return parse_error(0, "data packet without a 6DOF component");
  if (component->bodies.size() != bodies.size()) {
    return parse_error(0, "6DOF component has " + std::to_string(component->bodies.size()) +
                              " bodies but the parameters list " + std::to_string(bodies.size()));
  }
  MappedFrame out;
  core::MocapFrame& f = out.frame;
  f.frame_number = data.frame_number;
  if (data.timestamp_us >= 0) {
    f.capture_time = core::SourceTime{std::chrono::microseconds(data.timestamp_us)};
  }
  if (frequency_hz && *frequency_hz > 0.0 && std::isfinite(*frequency_hz)) {
    f.frame_rate_hz = *frequency_hz;
  }
  const bool matrix = has_matrix(component->type);
  f.bodies.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body6d& b = component->bodies[i];
    core::BodySample body;
    body.name = bodies[i].name;
    if (!all_nan(b, matrix)) {
      const Eigen::Vector3d t_mm(b.position_mm[0], b.position_mm[1], b.position_mm[2]);
      const auto q = orientation(b, matrix);
      if (q && t_mm.allFinite()) {
        body.tracked = true;
        body.p_world_m = t_mm / 1000.0;
        body.q_world_body = *q;
      } else {
        ++out.invalid_poses;
        body.mirrored = matrix && vicon::is_mirrored_rotation(row_major(b));
      }
    }
    f.bodies.push_back(std::move(body));
  }
  return out;
}

std::array<double, 3> euler_from_quaternion(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  // R = Rx(a)·Ry(b)·Rz(c): r02 = sin b, r12 = −sin a cos b, r22 = cos a cos b,
  // r01 = −cos b sin c, r00 = cos b cos c.
  const double b = std::asin(std::clamp(r(0, 2), -1.0, 1.0));
  const double a = std::atan2(-r(1, 2), r(2, 2));
  const double c = std::atan2(-r(0, 1), r(0, 0));
  return {a / kDeg, b / kDeg, c / kDeg};
}

Eigen::Quaterniond quaternion_from_euler(const std::array<double, 3>& deg) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(deg[0] * kDeg, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(deg[1] * kDeg, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(deg[2] * kDeg, Eigen::Vector3d::UnitZ());
  return q.normalized();
}

Body6d body_from_sample(const core::BodySample& sample, float residual_mm) {
  Body6d b;
  if (!sample.tracked) {
    constexpr float nan = std::numeric_limits<float>::quiet_NaN();
    b.position_mm.fill(nan);
    b.rotation.fill(nan);
    b.euler_deg.fill(nan);
    b.residual = nan;
    return b;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    b.position_mm[i] = static_cast<float>(sample.p_world_m[static_cast<Eigen::Index>(i)] * 1000.0);
  }
  const Eigen::Matrix3d r = sample.q_world_body.normalized().toRotationMatrix();
  for (std::size_t col = 0; col < 3; ++col) {
    for (std::size_t row = 0; row < 3; ++row) {
      b.rotation[col * 3 + row] =
          static_cast<float>(r(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(col)));
    }
  }
  const auto euler = euler_from_quaternion(sample.q_world_body);
  for (std::size_t i = 0; i < 3; ++i) b.euler_deg[i] = static_cast<float>(euler[i]);
  b.residual = residual_mm;
  return b;
}

ServedFrame served_frame(const core::MocapFrame& frame) {
  ServedFrame out;
  const auto us =
      std::chrono::duration_cast<std::chrono::microseconds>(frame.capture_time.time_since_epoch());
  out.timestamp_us = us.count();
  out.frame_number = static_cast<std::uint32_t>(frame.frame_number);
  out.names.reserve(frame.bodies.size());
  out.bodies.reserve(frame.bodies.size());
  for (const auto& b : frame.bodies) {
    out.names.push_back(b.name);
    out.bodies.push_back(body_from_sample(b, 0.5f));
  }
  return out;
}

}  // namespace mocaplink::wire::qtm

#include "mocaplink/wire/vicon_pose.hpp"

#include <algorithm>
#include <cmath>

namespace mocaplink::wire::vicon {

namespace {

Eigen::Matrix3d to_matrix(const std::array<double, 9>& r) {
  Eigen::Matrix3d m;
  m << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  return m;
}

bool is_orthonormal(const Eigen::Matrix3d& m) {
  if (!m.allFinite()) return false;
  const Eigen::Matrix3d err = m.transpose() * m - Eigen::Matrix3d::Identity();
  return err.cwiseAbs().maxCoeff() <= kRotationTolerance;
}

bool is_rotation(const Eigen::Matrix3d& m) {
  return is_orthonormal(m) && std::abs(m.determinant() - 1.0) <= kRotationTolerance;
}

// The Y-up → Z-up change of basis of §9.4.
const Eigen::Matrix3d& y_up_basis() {
  static const Eigen::Matrix3d q = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  return q;
}

}  // namespace

bool is_mirrored_rotation(const std::array<double, 9>& r) {
  const Eigen::Matrix3d m = to_matrix(r);
  return is_orthonormal(m) && std::abs(m.determinant() + 1.0) <= kRotationTolerance;
}

std::optional<Eigen::Quaterniond> quaternion_from_rotation(const std::array<double, 9>& r) {
  const Eigen::Matrix3d m = to_matrix(r);
  if (!is_rotation(m)) return std::nullopt;
  const double trace = m(0, 0) + m(1, 1) + m(2, 2);
  double w = 0;
  double x = 0;
  double y = 0;
  double z = 0;
  if (trace > 0.0) {
    // Shoemake: w = ½√(1+trace) > 0 (§9.2).
    const double s = std::sqrt(1.0 + trace) * 2.0;  // 4w
    w = 0.25 * s;
    x = (m(2, 1) - m(1, 2)) / s;
    y = (m(0, 2) - m(2, 0)) / s;
    z = (m(1, 0) - m(0, 1)) / s;
  } else if (m(0, 0) >= m(1, 1) && m(0, 0) >= m(2, 2)) {
    const double s = std::sqrt(1.0 + m(0, 0) - m(1, 1) - m(2, 2)) * 2.0;  // 4x
    x = 0.25 * s;
    w = (m(2, 1) - m(1, 2)) / s;
    y = (m(0, 1) + m(1, 0)) / s;
    z = (m(0, 2) + m(2, 0)) / s;
  } else if (m(1, 1) >= m(2, 2)) {
    const double s = std::sqrt(1.0 + m(1, 1) - m(0, 0) - m(2, 2)) * 2.0;  // 4y
    y = 0.25 * s;
    w = (m(0, 2) - m(2, 0)) / s;
    x = (m(0, 1) + m(1, 0)) / s;
    z = (m(1, 2) + m(2, 1)) / s;
  } else {
    const double s = std::sqrt(1.0 + m(2, 2) - m(0, 0) - m(1, 1)) * 2.0;  // 4z
    z = 0.25 * s;
    w = (m(1, 0) - m(0, 1)) / s;
    x = (m(0, 2) + m(2, 0)) / s;
    y = (m(1, 2) + m(2, 1)) / s;
  }
  Eigen::Quaterniond q(w, x, y, z);
  q.normalize();
  return q;
}

std::array<double, 9> rotation_from_quaternion(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d m = q.normalized().toRotationMatrix();
  return {m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)};
}

Eigen::Vector3d y_up_to_z_up(const Eigen::Vector3d& t) {
  return y_up_basis().transpose() * t;
}

Eigen::Quaterniond y_up_to_z_up(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d r = y_up_basis().transpose() * q.toRotationMatrix() * y_up_basis();
  Eigen::Quaterniond out(r);
  out.normalize();
  return out;
}

}  // namespace mocaplink::wire::vicon

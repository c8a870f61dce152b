#include "mocaplink/core/ros.hpp"

#include <algorithm>
#include <cctype>

#include "mocaplink/core/geodesy.hpp"

namespace mocaplink::core {
namespace {

bool is_token_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

/// Why `name` (tokens separated by single '/', no leading or trailing '/') breaks ROS's rules.
std::optional<std::string> tokens_problem(std::string_view name) {
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t end = std::min(name.find('/', start), name.size());
    const std::string_view token = name.substr(start, end - start);
    if (token.empty()) return "has an empty token (\"//\" or a '/' at an end)";
    for (const char c : token) {
      if (!is_token_char(c)) {
        return "may hold only letters, digits, '_' and '/', not '" + std::string(1, c) + "'";
      }
    }
    if (std::isdigit(static_cast<unsigned char>(token.front())) != 0) {
      return "has a token that starts with a digit (\"" + std::string(token) + "\")";
    }
    if (token.find("__") != std::string_view::npos) return "may not hold \"__\"";
    start = end + 1;
  }
  return std::nullopt;
}

/// Rows of the rotation target ← NED (world) and target ← FRD (body) for each RosAxes.
/// The matrix of ned_enu_swap (geodesy.hpp, the one NED ↔ ENU convention): its columns are the
/// swapped unit vectors.
Eigen::Matrix3d enu_from_ned() {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) m.col(i) = ned_enu_swap(Eigen::Vector3d::Unit(i));
  return m;
}

Eigen::Matrix3d flu_from_frd() {
  return Eigen::Vector3d(1, -1, -1).asDiagonal();
}

Matrix6d block_rotate(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, const Matrix6d& m) {
  Matrix6d r = Matrix6d::Zero();
  r.topLeftCorner<3, 3>() = a;
  r.bottomRightCorner<3, 3>() = b;
  // Exactly symmetric again: R Σ Rᵀ leaves (i, j) and (j, i) apart by rounding, and a subscriber
  // that checks Σ == Σᵀ (or factors it) would reject the message.
  const Matrix6d out = r * m * r.transpose();
  return 0.5 * (out + out.transpose());
}

}  // namespace

std::string ros_name_token(std::string_view body) {
  std::string out;
  out.reserve(body.size() + 1);
  for (const char c : body) {
    const char mapped = is_token_char(c) ? c : '_';
    if (mapped == '_' && (out.empty() || out.back() == '_')) continue;  // no leading "_", no "__"
    out.push_back(mapped);
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  if (!out.empty() && std::isdigit(static_cast<unsigned char>(out.front())) != 0) {
    out.insert(out.begin(), '_');
  }
  return out;
}

std::optional<std::string> ros_namespace_problem(std::string_view ns) {
  if (!ns.empty() && ns.front() == '/') ns.remove_prefix(1);
  if (ns.empty()) return std::nullopt;
  return tokens_problem(ns);
}

std::optional<std::string> ros_frame_id_problem(std::string_view frame_id) {
  if (frame_id.empty()) return "may not be empty";
  if (frame_id.front() == '/') return "may not start with '/' (tf2 frame ids are relative)";
  return tokens_problem(frame_id);
}

std::string ros_body_topic(std::string_view ns, std::string_view body, std::string_view leaf) {
  if (!ns.empty() && ns.front() == '/') ns.remove_prefix(1);
  std::string topic = "/";
  if (!ns.empty()) {
    topic += ns;
    topic += '/';
  }
  topic += body;
  topic += '/';
  topic += leaf;
  return topic;
}

std::string_view to_string(RosAxes axes) {
  switch (axes) {
    case RosAxes::enu_flu:
      return "enu_flu";
    case RosAxes::mocap:
      return "mocap";
  }
  return "unknown";
}

RosBodyState ros_body_state(const BodyEstimate& estimate, RosAxes axes,
                            const WorldAxisMapping& world, const BodyAxisMapping& body) {
  // W: target world ← NED; B: target body ← FRD. Both proper rotations, so the orientation stays a
  // rotation: R_target = W · R_ned_frd · Bᵀ.
  const Eigen::Matrix3d w =
      axes == RosAxes::enu_flu ? enu_from_ned() : Eigen::Matrix3d(world.r_ned_world().transpose());
  const Eigen::Matrix3d b = axes == RosAxes::enu_flu ? flu_from_frd() : body.r_body_frd();
  const Eigen::Matrix3d r_ned_frd = estimate.q_ned_frd.toRotationMatrix();
  RosBodyState s;
  s.position_m = w * estimate.p_ned_m;
  // As quaternions, so the tracker's sign continuity is kept (a matrix → quaternion would pick
  // w ≥ 0 and flip an estimate whose w went negative).
  s.orientation =
      (Eigen::Quaterniond(w) * estimate.q_ned_frd * Eigen::Quaterniond(b).conjugate()).normalized();
  s.linear_velocity_mps = b * estimate.v_frd_mps();
  s.angular_velocity_radps = b * estimate.w_frd_radps;
  // Attitude error about the FRD axes → about the target world's fixed axes: W · R_ned_frd.
  s.pose_covariance = block_rotate(w, w * r_ned_frd, estimate.pose_covariance);
  s.twist_covariance = block_rotate(b, b, estimate.velocity_covariance_frd());
  return s;
}

}  // namespace mocaplink::core

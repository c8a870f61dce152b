// Gravity against mocap, and the axis settings that fit (axis_fix.hpp).
#include "mocaplink/core/axis_fix.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numbers>

namespace mocaplink::core {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// The angle between two unit vectors (deg), robust near 0 and 180 (atan2 of |a×b| and a·b).
double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

/// Degrees to (−180, 180].
double wrap_deg(double deg) {
  double d = std::fmod(deg, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

}  // namespace

Eigen::Vector3d down_frd_from_roll_pitch(double roll_rad, double pitch_rad) {
  // Third row of R_ned_frd = Rz(ψ) Ry(θ) Rx(φ): independent of ψ.
  return {-std::sin(pitch_rad), std::sin(roll_rad) * std::cos(pitch_rad),
          std::cos(roll_rad) * std::cos(pitch_rad)};
}

double tilt_offset_deg(const Eigen::Quaterniond& q_ned_frd, double roll_rad, double pitch_rad) {
  if (!std::isfinite(roll_rad) || !std::isfinite(pitch_rad) || !q_ned_frd.coeffs().allFinite()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const Eigen::Vector3d mocap = q_ned_frd.normalized().toRotationMatrix().row(2).transpose();
  return angle_deg(down_frd_from_roll_pitch(roll_rad, pitch_rad), mocap);
}

std::string_view to_string(AxisFixKind kind) {
  switch (kind) {
    case AxisFixKind::agrees:
      return "agrees";
    case AxisFixKind::fix:
      return "fix";
    case AxisFixKind::mirror:
      return "mirror";
    case AxisFixKind::no_fit:
      return "no_fit";
  }
  return "no_fit";
}

namespace {

constexpr std::array<SignedAxis, 6> kAxes{axis::pos_x, axis::neg_x, axis::pos_y,
                                          axis::neg_y, axis::pos_z, axis::neg_z};

struct Candidate {
  AxisSettings settings;
  double tilt_deg = 0.0;
  std::optional<double> heading_deg;
  bool configurable = true;  ///< proper on both sides and overall
  double cost = 0.0;
  [[nodiscard]] bool fits() const {
    return tilt_deg <= kMaxTiltOffsetDeg && (!heading_deg || *heading_deg <= kMaxHeadingOffsetDeg);
  }
  [[nodiscard]] double residual() const { return tilt_deg + heading_deg.value_or(0.0); }
};

Candidate judge(const Eigen::Matrix3d& m, const VehicleAtRest& vehicle) {
  Candidate c;
  c.tilt_deg = angle_deg(down_frd_from_roll_pitch(vehicle.roll_rad, vehicle.pitch_rad),
                         m.row(2).transpose());
  if (vehicle.heading_rad) {
    const double yaw = std::atan2(m(1, 0), m(0, 0));
    c.heading_deg = std::abs(wrap_deg((*vehicle.heading_rad - yaw) * kDegPerRad));
  }
  c.configurable = m.determinant() > 0.0;
  return c;
}

double cost(const AxisSettings& s, const AxisSettings& current,
            const std::optional<SignedAxis>& source_up) {
  double c = 0.0;
  c += s.up == current.up ? 0.0 : 1.0;
  c += s.north == current.north ? 0.0 : 1.25;
  c += s.body_forward == current.body_forward ? 0.0 : 1.0;
  c += s.body_up == current.body_up ? 0.0 : 1.0;
  if (source_up && s.up != *source_up) c += 0.5;
  return c;
}

std::vector<std::string> lines_between(const AxisSettings& from, const AxisSettings& to) {
  std::vector<std::string> out;
  auto line = std::back_inserter(out);
  if (to.up != from.up) *line = "[mocap] up = \"" + to_string(to.up) + "\"";
  if (to.north != from.north) *line = "[mocap] north = \"" + to_string(to.north) + "\"";
  if (to.body_forward != from.body_forward) {
    *line = "[[vehicle]] body_forward = \"" + to_string(to.body_forward) + "\"";
  }
  if (to.body_up != from.body_up) {
    *line = "[[vehicle]] body_up = \"" + to_string(to.body_up) + "\"";
  }
  return out;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += (out.empty() ? "" : ", ") + l;
  return out;
}

std::string degrees(double deg) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.1f°", deg);
  return text.data();
}

/// "tilt 0.3°, heading 2.0° from the vehicle's own heading" / "tilt 0.3°, nose unchecked: ..."
std::string residual_text(const Candidate& c) {
  std::string out = "tilt " + degrees(c.tilt_deg);
  if (c.heading_deg) return out + ", heading " + degrees(*c.heading_deg);
  return out + ", nose unchecked: the vehicle has no heading of its own";
}

}  // namespace

AxisFix find_axis_fix(const Eigen::Matrix3d& r_world_body, const AxisSettings& current,
                      const VehicleAtRest& vehicle, std::optional<SignedAxis> source_up) {
  const Eigen::Matrix3d flip_y = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
  std::vector<Candidate> all;
  all.reserve(6 * 5 * 24 * 3);
  for (const SignedAxis up : kAxes) {
    std::vector<North> norths;
    for (const SignedAxis n : kAxes) {
      if (are_perpendicular(up, n)) norths.emplace_back(n);
    }
    if (std::holds_alternative<NorthAngle>(current.north)) norths.push_back(current.north);
    for (const North& north : norths) {
      const auto world = WorldAxisMapping::make(up, north);
      if (!world) continue;
      for (const SignedAxis forward : kAxes) {
        for (const SignedAxis body_up : kAxes) {
          const auto body = BodyAxisMapping::make(forward, body_up);
          if (!body) continue;
          const Eigen::Matrix3d m = world->r_ned_world() * r_world_body * body->r_body_frd();
          const AxisSettings s{up, north, forward, body_up};
          // The settings as written, then a mirror on either side (not configurable).
          Candidate c = judge(m, vehicle);
          c.settings = s;
          c.cost = cost(s, current, source_up);
          all.push_back(c);
          for (const Eigen::Matrix3d& mirrored :
               {Eigen::Matrix3d(flip_y * m), Eigen::Matrix3d(m * flip_y)}) {
            Candidate mc = judge(mirrored, vehicle);
            mc.settings = s;
            mc.configurable = false;
            all.push_back(mc);
          }
        }
      }
    }
  }
  AxisFix out;
  const auto better = [](const Candidate& a, const Candidate& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    return a.residual() < b.residual();
  };
  const Candidate* best = nullptr;
  const Candidate* closest = nullptr;
  const Candidate* mirror = nullptr;
  for (const Candidate& c : all) {
    if (closest == nullptr || c.residual() < closest->residual()) closest = &c;
    if (!c.fits()) continue;
    if (!c.configurable) {
      if (mirror == nullptr || c.residual() < mirror->residual()) mirror = &c;
    } else if (best == nullptr || better(c, *best)) {
      best = &c;
    }
  }
  if (best != nullptr && best->settings == current) {
    out.kind = AxisFixKind::agrees;
    out.settings = current;
    out.tilt_residual_deg = best->tilt_deg;
    out.heading_residual_deg = best->heading_deg;
    out.text = "no axis change needed: the settings fit the vehicle at rest (" +
               residual_text(*best) + ")";
    return out;
  }
  if (best != nullptr) {
    out.kind = AxisFixKind::fix;
    out.settings = best->settings;
    out.tilt_residual_deg = best->tilt_deg;
    out.heading_residual_deg = best->heading_deg;
    out.lines = lines_between(current, best->settings);
    // Another choice as small (as many lines) and about as close: the cheapest such.
    const Candidate* other = nullptr;
    for (const Candidate& c : all) {
      if (&c == best || !c.configurable || !c.fits() || c.settings == best->settings) continue;
      if (c.residual() > best->residual() + 2.0) continue;
      if (lines_between(current, c.settings).size() != out.lines.size()) continue;
      if (other == nullptr || better(c, *other)) other = &c;
    }
    if (other != nullptr) out.alternative_lines = lines_between(current, other->settings);
    out.text = "fix: " + joined(out.lines) + " (then " + residual_text(*best) + ")";
    if (!out.alternative_lines.empty()) {
      // With a heading, two fits of the same up differ by a turn about the vertical: a nose
      // turned on the body or an arena whose north is turned, which no pose at rest tells
      // apart (every vehicle showing the same heading offset says it is the arena). Without
      // one, a wrong up and a wrong body_up differ with the pose: yawing the vehicle decides.
      const bool turned = vehicle.heading_rad && other->settings.up == best->settings.up;
      out.text += turned ? "; or, if it is the arena's north that is turned (no pose at rest "
                           "tells the two apart): "
                         : "; or, as well at this pose: ";
      out.text += joined(out.alternative_lines);
    }
    return out;
  }
  if (mirror != nullptr) {
    out.kind = AxisFixKind::mirror;
    out.tilt_residual_deg = mirror->tilt_deg;
    out.heading_residual_deg = mirror->heading_deg;
    out.text =
        "mirrored: only a left-handed axis choice makes mocap agree with the vehicle (" +
        residual_text(*mirror) +
        "); no up, north, body_forward or body_up setting can fix it: check the handedness of "
        "the mocap system's or its streaming tool's frame";
    return out;
  }
  out.kind = AxisFixKind::no_fit;
  if (closest != nullptr) {
    out.tilt_residual_deg = closest->tilt_deg;
    out.heading_residual_deg = closest->heading_deg;
  }
  out.text = "no axis choice makes mocap agree with the vehicle (closest: " +
             (closest != nullptr ? residual_text(*closest) : std::string("none")) +
             "): is the vehicle at rest, and is this its rigid body?";
  return out;
}

}  // namespace mocaplink::core

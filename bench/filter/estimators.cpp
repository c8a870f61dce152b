#include "estimators.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include <Eigen/Dense>

namespace mocaplink::bench {
namespace {

const Eigen::Vector3d& measured(const Sample& s, bool clean) {
  return clean ? s.p_clean_m : s.p_meas_m;
}

bool received(const Sample& s) {
  return !s.dropped && s.tracked;
}

}  // namespace

std::vector<Output> run_tracker(const std::vector<Sample>& samples, bool clean,
                                const core::TrackerConfig& config) {
  core::Tracker tracker(config);
  std::vector<Output> out;
  for (const Sample& s : samples) {
    if (s.dropped) continue;  // the frame never arrived: the Station calls nothing
    const auto t = core::source_time_from_ns(std::llround(s.t_s * 1e9));
    if (s.tracked) {
      tracker.on_pose_ned(t, measured(s, clean), Eigen::Quaterniond::Identity());
    } else {
      tracker.on_missing(t);
    }
    const core::BodyEstimate& e = tracker.estimate();
    if (e.pose_valid()) out.push_back({s.t_s, e.p_ned_m, e.v_ned_mps});
  }
  return out;
}

std::vector<Output> run_finite_difference(const std::vector<Sample>& samples, bool clean) {
  std::vector<Output> out;
  std::optional<Sample> previous;
  for (const Sample& s : samples) {
    if (!received(s)) continue;
    if (previous) {
      const double dt = s.t_s - previous->t_s;
      out.push_back(
          {s.t_s, measured(s, clean), (measured(s, clean) - measured(*previous, clean)) / dt});
    }
    previous = s;
  }
  return out;
}

std::vector<Output> run_finite_difference_lowpass(const std::vector<Sample>& samples, bool clean,
                                                  double rate_hz) {
  // Second-order Butterworth via the bilinear transform: k = tan(pi fc / fs).
  constexpr double kCutoffHz = 30.0;
  const double k = std::tan(std::numbers::pi * kCutoffHz / rate_hz);
  const double q = std::numbers::sqrt2;  // 1/Q for Butterworth
  const double norm = 1.0 / (1.0 + q * k + k * k);
  const double b0 = k * k * norm;
  const double b1 = 2.0 * b0;
  const double b2 = b0;
  const double a1 = 2.0 * (k * k - 1.0) * norm;
  const double a2 = (1.0 - q * k + k * k) * norm;
  Eigen::Vector3d x1 = Eigen::Vector3d::Zero(), x2 = x1, y1 = x1, y2 = x1;
  bool primed = false;
  std::vector<Output> out;
  for (const Output& fd : run_finite_difference(samples, clean)) {
    if (!primed) {  // start in steady state at the first value
      x1 = x2 = y1 = y2 = fd.v_ned_mps;
      primed = true;
    }
    const Eigen::Vector3d y = b0 * fd.v_ned_mps + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1;
    x1 = fd.v_ned_mps;
    y2 = y1;
    y1 = y;
    out.push_back({fd.t_s, fd.p_ned_m, y});
  }
  return out;
}

std::vector<Output> run_original(const std::vector<Sample>& samples, bool clean, double rate_hz) {
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  constexpr double kSendRateHz = 10.0;
  Matrix6d q = Matrix6d::Zero();
  q.topLeftCorner<3, 3>().setIdentity();
  q.topRightCorner<3, 3>().setIdentity();
  q.bottomLeftCorner<3, 3>().setIdentity();
  q.bottomRightCorner<3, 3>().setIdentity();
  const Eigen::Matrix3d r = 0.01 * Eigen::Matrix3d::Identity();
  Vector6d x = Vector6d::Zero();
  Matrix6d p = Matrix6d::Zero();
  bool initialised = false;
  std::uint64_t last_frame = 0;
  std::vector<Output> out;
  std::size_t next = 0;
  std::optional<Sample> latest;
  const double end = samples.empty() ? 0.0 : samples.back().t_s;
  for (int tick = 1; tick / kSendRateHz <= end; ++tick) {
    const double now = tick / kSendRateHz;
    while (next < samples.size() && samples[next].t_s <= now) {
      if (received(samples[next])) latest = samples[next];
      ++next;
    }
    if (!latest) continue;
    const Eigen::Vector3d z = measured(*latest, clean);
    if (!initialised) {
      x << z, Eigen::Vector3d::Zero();
      p.setZero();
      p.topLeftCorner<3, 3>().diagonal().setConstant(0.1);
      p.bottomRightCorner<3, 3>().diagonal().setConstant(10.0);
      initialised = true;
      last_frame = latest->frame;
      continue;
    }
    const double dt = latest->frame > last_frame
                          ? static_cast<double>(latest->frame - last_frame) / rate_hz
                          : 1.0 / kSendRateHz;
    last_frame = latest->frame;
    Matrix6d f = Matrix6d::Identity();
    f.topRightCorner<3, 3>().diagonal().setConstant(dt);
    x = f * x;
    p = f * p * f.transpose() + q;
    const Eigen::Matrix3d s = p.topLeftCorner<3, 3>() + r;
    const Eigen::Matrix<double, 6, 3> k = p.leftCols<3>() * s.inverse();
    x += k * (z - x.head<3>());
    Matrix6d i_kh = Matrix6d::Identity();
    i_kh.leftCols<3>() -= k;
    p = i_kh * p;
    out.push_back({latest->t_s, x.head<3>(), x.tail<3>()});
  }
  return out;
}

}  // namespace mocaplink::bench

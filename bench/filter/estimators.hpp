// The velocity estimators compared by the filter-accuracy harness.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mocaplink/core/tracker.hpp"
#include "scenario.hpp"

namespace mocaplink::bench {

/// One output of an estimator: what it would send at time t_s (the capture time of the newest
/// sample it used), position and velocity in NED.
struct Output {
  double t_s = 0.0;
  Eigen::Vector3d p_ned_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ned_mps = Eigen::Vector3d::Zero();
};

/// `clean`: use Sample::p_clean_m (the counterfactual run without outliers).
/// mocaplink's Tracker on every frame; outputs only where BodyEstimate::pose_valid().
std::vector<Output> run_tracker(const std::vector<Sample>& samples, bool clean,
                                const core::TrackerConfig& config);
/// Backward finite differences between consecutive received samples, dt from timestamps.
std::vector<Output> run_finite_difference(const std::vector<Sample>& samples, bool clean);
/// Finite differences through a 2-pole Butterworth low-pass at 30 Hz designed for the nominal
/// rate (bilinear transform with pre-warping), one filter step per received sample: MAVProxy-like.
std::vector<Output> run_finite_difference_lowpass(const std::vector<Sample>& samples, bool clean,
                                                  double rate_hz);
/// The original ViconMAVLink Sender filter, rewritten from its description: a constant-velocity
/// Kalman filter stepped once per 10 Hz send tick on the latest sample, dt = frames elapsed /
/// mocap rate (1/10 s if no new frame), the same Q = [I I; I I] at every step, R = 0.01 I m^2,
/// P0 = diag(0.1, 0.1, 0.1, 10, 10, 10), velocity starting at zero.
std::vector<Output> run_original(const std::vector<Sample>& samples, bool clean, double rate_hz);

}  // namespace mocaplink::bench

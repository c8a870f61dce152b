// Synthetic mocap data for the filter-accuracy harness: analytic trajectories (exact truth
// position and velocity) sampled at a mocap rate with the faults issue 3 lists.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mocaplink::bench {

/// Exact position (m) and velocity (m/s) in NED at time t (s).
struct Truth {
  Eigen::Vector3d p_ned_m;
  Eigen::Vector3d v_ned_mps;
};
using Trajectory = std::function<Truth(double t_s)>;

struct Scenario {
  std::string name;
  Trajectory truth;
  double duration_s = 30.0;
};

/// Hover at 1 m with a small oscillation (1 cm / 1 cm / 0.5 cm at 0.5 / 0.3 / 0.7 Hz).
Scenario hover_scenario();
/// Figure-eight (Gerono lemniscate, 3 m x 1.5 m) at a mean speed of 2 m/s.
Scenario figure_eight_scenario();
/// 1 m point-to-point moves, bang-bang at 5 m/s^2 (peak 2.24 m/s), 1 s hold between moves,
/// cycling +x, +y, -x, -y.
Scenario point_to_point_scenario();

/// Fault model applied to the samples.
struct Faults {
  double noise_m = 0.0005;          ///< Gaussian per axis
  double drop_probability = 0.02;   ///< whole frame missing
  double occlusion_start_s = 12.0;  ///< body flagged untracked for occlusion_s
  double occlusion_s = 0.2;
  double outliers_per_s = 0.5;  ///< 10 cm single-frame jumps in a random direction
  double outlier_m = 0.1;
};

/// One mocap frame as the Station would see it.
struct Sample {
  std::uint64_t frame = 0;
  double t_s = 0.0;
  bool dropped = false;  ///< the frame never arrived
  bool tracked = true;   ///< false inside the occlusion
  bool outlier = false;  ///< p_meas carries a 10 cm jump
  Eigen::Vector3d p_meas_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_clean_m = Eigen::Vector3d::Zero();  ///< the same sample without the jump
};

/// Deterministic (seeded) samples at rate_hz.
std::vector<Sample> make_samples(const Scenario& scenario, double rate_hz, const Faults& faults,
                                 std::uint32_t seed);

}  // namespace mocaplink::bench

// Accuracy figures of an estimator's outputs against the exact trajectory.
#pragma once

#include <cstddef>
#include <vector>

#include "estimators.hpp"
#include "scenario.hpp"

namespace mocaplink::bench {

/// Outputs before this time are not scored: every estimator starts from zero velocity and the
/// first second is its convergence, not its accuracy.
inline constexpr double kWarmUpS = 1.0;

/// sqrt(mean |v_est - v_true|^2) over all outputs after kWarmUpS, m/s (3-D error).
double velocity_rmse(const std::vector<Output>& outputs, const Trajectory& truth);

/// The delay tau (s) that best explains the estimate as a delayed truth: argmin over tau of
/// sum |v_est(t) - v_true(t - tau)|^2, after kWarmUpS, searched over [-20 ms, 400 ms] (1 ms grid,
/// then 0.05 ms).
double velocity_lag_s(const std::vector<Output>& outputs, const Trajectory& truth);

/// Injected outliers that reached the output: an outlier counts when, within 100 ms after it,
/// the run with outliers differs from the same run without them (Sample::p_clean_m) by more than
/// 1 cm in position or 0.25 m/s in velocity (a 10 cm jump fused by any of
/// the estimators moves them by far more; fusing or not one clean sample moves them far less). Both
/// runs must come from the same samples.
std::size_t outliers_in_output(const std::vector<Sample>& samples,
                               const std::vector<Output>& with_outliers,
                               const std::vector<Output>& without_outliers);

}  // namespace mocaplink::bench

#include "metrics.hpp"

#include <cmath>
#include <limits>

namespace mocaplink::bench {
namespace {

double squared_error_at_lag(const std::vector<Output>& outputs, const Trajectory& truth,
                            double tau) {
  double sum = 0.0;
  for (const Output& o : outputs) {
    if (o.t_s < kWarmUpS) continue;
    sum += (o.v_ned_mps - truth(o.t_s - tau).v_ned_mps).squaredNorm();
  }
  return sum;
}

}  // namespace

double velocity_rmse(const std::vector<Output>& outputs, const Trajectory& truth) {
  std::size_t n = 0;
  for (const Output& o : outputs) n += o.t_s >= kWarmUpS ? 1 : 0;
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(squared_error_at_lag(outputs, truth, 0.0) / static_cast<double>(n));
}

double velocity_lag_s(const std::vector<Output>& outputs, const Trajectory& truth) {
  double best_tau = 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (int ms = -20; ms <= 400; ++ms) {
    const double e = squared_error_at_lag(outputs, truth, ms * 1e-3);
    if (e < best) {
      best = e;
      best_tau = ms * 1e-3;
    }
  }
  const double coarse = best_tau;
  for (int i = -20; i <= 20; ++i) {
    const double tau = coarse + i * 5e-5;
    const double e = squared_error_at_lag(outputs, truth, tau);
    if (e < best) {
      best = e;
      best_tau = tau;
    }
  }
  return best_tau;
}

std::size_t outliers_in_output(const std::vector<Sample>& samples,
                               const std::vector<Output>& with_outliers,
                               const std::vector<Output>& without_outliers) {
  std::size_t count = 0;
  const std::size_t n = std::min(with_outliers.size(), without_outliers.size());
  for (const Sample& s : samples) {
    if (!s.outlier || s.dropped || !s.tracked) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const Output& a = with_outliers[i];
      const Output& b = without_outliers[i];
      if (a.t_s < s.t_s || a.t_s > s.t_s + 0.1 || a.t_s != b.t_s) continue;
      if ((a.p_ned_m - b.p_ned_m).norm() > 0.01 || (a.v_ned_mps - b.v_ned_mps).norm() > 0.25) {
        ++count;
        break;
      }
    }
  }
  return count;
}

}  // namespace mocaplink::bench

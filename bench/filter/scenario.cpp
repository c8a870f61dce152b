#include "scenario.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace mocaplink::bench {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

Scenario hover_scenario() {
  return {"hover", [](double t) {
            const double w1 = kTwoPi * 0.5, w2 = kTwoPi * 0.3, w3 = kTwoPi * 0.7;
            Truth out;
            out.p_ned_m = {0.01 * std::sin(w1 * t), 0.01 * std::sin(w2 * t + 1.0),
                           -1.0 + 0.005 * std::sin(w3 * t)};
            out.v_ned_mps = {0.01 * w1 * std::cos(w1 * t), 0.01 * w2 * std::cos(w2 * t + 1.0),
                             0.005 * w3 * std::cos(w3 * t)};
            return out;
          }};
}

Scenario figure_eight_scenario() {
  // x = A sin(wt), y = (A/2) sin(2wt): speed = A w sqrt(cos^2(wt) + cos^2(2wt)). The mean of the
  // square root over a period is computed numerically so that the mean speed is 2 m/s.
  constexpr double kA = 1.5;
  constexpr int kSteps = 100000;
  double mean = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double phi = kTwoPi * (i + 0.5) / kSteps;
    mean += std::hypot(std::cos(phi), std::cos(2.0 * phi));
  }
  mean /= kSteps;
  const double w = 2.0 / (kA * mean);
  return {"figure-eight", [w](double t) {
            Truth out;
            out.p_ned_m = {kA * std::sin(w * t), 0.5 * kA * std::sin(2.0 * w * t), -1.0};
            out.v_ned_mps = {kA * w * std::cos(w * t), kA * w * std::cos(2.0 * w * t), 0.0};
            return out;
          }};
}

Scenario point_to_point_scenario() {
  constexpr double kAccel = 5.0;
  const double t_a = std::sqrt(1.0 / kAccel);  // half a 1 m move
  const double move = 2.0 * t_a;
  const double leg = move + 1.0;  // move, then hold 1 s
  return {"point-to-point", [=](double t) {
            const Eigen::Vector3d dirs[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
            const auto n = static_cast<long>(std::floor(t / leg));
            Eigen::Vector3d start(0, 0, -1);
            for (long i = 0; i < n % 4; ++i) start += dirs[i];
            const Eigen::Vector3d& d = dirs[n % 4];
            const double u = t - static_cast<double>(n) * leg;  // time into this leg
            double s = 1.0;
            double v = 0.0;
            if (u < t_a) {
              s = 0.5 * kAccel * u * u;
              v = kAccel * u;
            } else if (u < move) {
              const double r = move - u;
              s = 1.0 - 0.5 * kAccel * r * r;
              v = kAccel * r;
            }
            return Truth{start + s * d, v * d};
          }};
}

std::vector<Sample> make_samples(const Scenario& scenario, double rate_hz, const Faults& faults,
                                 std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, faults.noise_m);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto n = static_cast<std::uint64_t>(scenario.duration_s * rate_hz);
  const double outlier_probability = faults.outliers_per_s / rate_hz;
  std::vector<Sample> out;
  out.reserve(n);
  for (std::uint64_t k = 0; k < n; ++k) {
    Sample s;
    s.frame = k;
    s.t_s = static_cast<double>(k) / rate_hz;
    s.p_clean_m =
        scenario.truth(s.t_s).p_ned_m + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    s.p_meas_m = s.p_clean_m;
    s.dropped = uniform(rng) < faults.drop_probability;
    s.tracked = !(s.t_s >= faults.occlusion_start_s &&
                  s.t_s < faults.occlusion_start_s + faults.occlusion_s);
    // Outliers only on isolated frames (never two in a row), and not in the first second.
    const bool previous_outlier = !out.empty() && out.back().outlier;
    if (s.t_s > 1.0 && !previous_outlier && uniform(rng) < outlier_probability) {
      const Eigen::Vector3d dir = Eigen::Vector3d(noise(rng), noise(rng), noise(rng)).normalized();
      s.outlier = true;
      s.p_meas_m += faults.outlier_m * dir;
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace mocaplink::bench

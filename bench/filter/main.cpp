// Filter-accuracy harness (issue 3): velocity RMSE, lag and outliers in the output of mocaplink's
// Tracker versus finite differences, finite differences + 30 Hz low-pass, and the original
// ViconMAVLink filter, on synthetic trajectories with noise, drops, an occlusion and outliers.
//
//   filter_accuracy [--csv FILE] [--seed N] [--accel_noise_mps2 X] [--gate_sigma X] ...
//
// Prints a Markdown table (docs/performance.md "Filter accuracy"). --csv writes the velocity
// series of the figure-eight at 100 Hz for docs/img/filter.png (bench/filter/plot.gp).
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "estimators.hpp"
#include "metrics.hpp"
#include "scenario.hpp"

namespace mb = mocaplink::bench;
namespace mc = mocaplink::core;

namespace {

struct Row {
  const char* method;
  double rmse_all;
  double rmse_clean;
  double lag_ms;
  std::size_t outliers_out;
};

void write_csv(const std::string& path, const mb::Scenario& scenario,
               const std::vector<mb::Sample>& samples, const mc::TrackerConfig& config) {
  // Window of 3 s around the occlusion, so the plot shows a pass with the gap in it.
  const double from = 10.5, to = 13.5;
  std::ofstream out(path);
  out << "# method t_s vx_mps vy_mps (figure-eight, 100 Hz, with faults)\n";
  auto dump = [&](const char* name, const std::vector<mb::Output>& outputs) {
    for (const auto& o : outputs) {
      if (o.t_s < from || o.t_s > to) continue;
      out << name << ' ' << o.t_s << ' ' << o.v_ned_mps.x() << ' ' << o.v_ned_mps.y() << '\n';
    }
    out << "\n\n";  // gnuplot index separator
  };
  std::vector<mb::Output> truth;
  for (double t = from; t <= to; t += 0.001)
    truth.push_back({t, Eigen::Vector3d::Zero(), scenario.truth(t).v_ned_mps});
  dump("truth", truth);
  dump("tracker", mb::run_tracker(samples, false, config));
  dump("finite_difference", mb::run_finite_difference(samples, false));
  dump("fd_lowpass_30hz", mb::run_finite_difference_lowpass(samples, false, 100.0));
  dump("original_10hz", mb::run_original(samples, false, 100.0));
}

bool parse_double(std::string_view arg, const char* name, int& i, int argc, char** argv,
                  double& value) {
  if (arg != name || i + 1 >= argc) return false;
  value = std::strtod(argv[++i], nullptr);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  mc::TrackerConfig config;
  std::string csv;
  unsigned seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    double jump = 0;
    if (a == "--csv" && i + 1 < argc) {
      csv = argv[++i];
    } else if (a == "--seed" && i + 1 < argc) {
      seed = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
    } else if (parse_double(a, "--accel_noise_mps2", i, argc, argv, config.accel_noise_mps2) ||
               parse_double(a, "--position_noise_m", i, argc, argv, config.position_noise_m) ||
               parse_double(a, "--gate_sigma", i, argc, argv, config.gate_sigma) ||
               parse_double(a, "--gate_min_m", i, argc, argv, config.gate_min_m)) {
    } else if (parse_double(a, "--jump_confirm_frames", i, argc, argv, jump)) {
      config.jump_confirm_frames = static_cast<std::uint32_t>(jump);
    } else {
      std::fprintf(stderr,
                   "usage: filter_accuracy [--csv FILE] [--seed N] [--<tracker param> X]\n");
      return 2;
    }
  }

  std::printf(
      "| scenario | rate | method | velocity RMSE (m/s) | RMSE without outliers | lag (ms) "
      "| outliers in output |\n|---|---|---|---|---|---|---|\n");
  bool target_met = true;
  for (const auto& scenario :
       {mb::hover_scenario(), mb::figure_eight_scenario(), mb::point_to_point_scenario()}) {
    for (double rate : {100.0, 240.0}) {
      const auto samples = mb::make_samples(scenario, rate, mb::Faults{}, seed);
      std::size_t injected = 0;
      for (const auto& s : samples) injected += s.outlier && !s.dropped && s.tracked ? 1 : 0;
      auto row = [&](const char* name, const std::vector<mb::Output>& with,
                     const std::vector<mb::Output>& without) {
        return Row{name, mb::velocity_rmse(with, scenario.truth),
                   mb::velocity_rmse(without, scenario.truth),
                   1e3 * mb::velocity_lag_s(with, scenario.truth),
                   mb::outliers_in_output(samples, with, without)};
      };
      const Row rows[] = {
          row("mocaplink Tracker", mb::run_tracker(samples, false, config),
              mb::run_tracker(samples, true, config)),
          row("finite differences", mb::run_finite_difference(samples, false),
              mb::run_finite_difference(samples, true)),
          row("FD + 30 Hz 2-pole LPF", mb::run_finite_difference_lowpass(samples, false, rate),
              mb::run_finite_difference_lowpass(samples, true, rate)),
          row("original (10 Hz KF)", mb::run_original(samples, false, rate),
              mb::run_original(samples, true, rate)),
      };
      for (const Row& r : rows) {
        std::printf("| %s | %.0f Hz | %s | %.4f | %.4f | %.1f | %zu / %zu |\n",
                    scenario.name.c_str(), rate, r.method, r.rmse_all, r.rmse_clean, r.lag_ms,
                    r.outliers_out, injected);
      }
      const Row& ours = rows[0];
      const bool ok = ours.rmse_all <= 0.5 * rows[1].rmse_all &&
                      ours.rmse_all <= 0.5 * rows[3].rmse_all && ours.lag_ms < 5.0 &&
                      ours.outliers_out == 0;
      target_met = target_met && ok;
      if (!ok) std::fprintf(stderr, "target missed: %s at %.0f Hz\n", scenario.name.c_str(), rate);
    }
  }
  if (!csv.empty()) {
    const auto scenario = mb::figure_eight_scenario();
    write_csv(csv, scenario, mb::make_samples(scenario, 100.0, mb::Faults{}, seed), config);
  }
  std::printf("\ntarget (RMSE <= 0.5x FD and original, lag < 5 ms, no outlier out): %s\n",
              target_met ? "met" : "MISSED");
  return target_met ? 0 : 1;
}

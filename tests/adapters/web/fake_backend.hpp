// An in-test DashboardBackend: a small made-up lab (three bodies on known paths, vehicles whose
// send counters follow their rate) with the daemon's refusal rules (the configuration's, through
// config::add_vehicle / update_vehicle), so the dashboard server and
// page can be tested without the daemon. Time is injected (seconds) so tests are deterministic;
// the browser tests' fake server drives it from a steady clock.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/web/dashboard_backend.hpp"

namespace mocaplink::web::testing {

class FakeBackend final : public DashboardBackend {
 public:
  /// Two vehicles ("quad1" following Body1 with px4, "rover" following Body2 with classic).
  FakeBackend();

  StatusView status() override;
  std::optional<ApiError> apply(const VehicleChange& change) override;

  /// Sets the time status() reports the lab at (seconds since start, ≥ 0).
  void set_time(double t_s);
  /// Every change applied successfully, in order (refused ones are not recorded).
  std::vector<VehicleChange> applied() const;
  /// While frozen, status() keeps answering the picture of the moment it froze (as the daemon
  /// does when its loop is too slow to answer); changes are still applied.
  void set_status_frozen(bool frozen);
  /// Number of status() calls so far.
  int status_calls() const;

 private:
  struct Vehicle {
    VehicleView view;
    double sent_at_s = 0.0;  // counters accrue from here at rate_hz
    double sent_before = 0.0;
  };
  void accrue(Vehicle& vehicle) const;

  mutable std::mutex mutex_;
  double t_s_ = 0.0;
  int status_calls_ = 0;
  std::vector<Vehicle> vehicles_;
  config::Config config_;  // what the vehicles are, as the daemon's configuration says
  std::vector<VehicleChange> applied_;
  std::optional<StatusView> frozen_;
};

/// The made-up position of body `index` (0, 1, 2) at time t_s, in metres (source world, z up).
std::array<double, 3> fake_body_position(std::size_t index, double t_s);

}  // namespace mocaplink::web::testing

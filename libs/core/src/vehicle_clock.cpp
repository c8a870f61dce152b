#include "mocaplink/core/vehicle_clock.hpp"

#include <algorithm>
#include <cmath>

#include "mocaplink/core/line_fit.hpp"

namespace mocaplink::core {

std::string_view to_string(VehicleClockVerdict verdict) {
  switch (verdict) {
    case VehicleClockVerdict::measuring:
      return "measuring";
    case VehicleClockVerdict::steady:
      return "steady";
    case VehicleClockVerdict::unsteady:
      return "unsteady";
  }
  return "measuring";
}

bool VehicleClockMonitor::on_request(std::int64_t ts1_ns, HostTime arrival) {
  const VehicleClockVerdict before = figures_.verdict;
  if (last_ts1_ns_ && ts1_ns < *last_ts1_ns_ - kVehicleClockRestartStep.count()) restart();
  // A request reordered on the way (ts1 a little behind the latest) is still a fair sample.
  last_ts1_ns_ = last_ts1_ns_ ? std::max(*last_ts1_ns_, ts1_ns) : ts1_ns;
  ++figures_.requests;
  const Minimum sample{arrival, arrival.time_since_epoch().count() - ts1_ns};
  if (!window_start_) window_start_ = arrival;
  if (arrival - *window_start_ >= config_.window) {
    close_window();
    window_start_ = arrival;
  }
  if (!current_ || sample.host_minus_vehicle_ns < current_->host_minus_vehicle_ns) {
    current_ = sample;
  }
  return figures_.verdict != before;
}

void VehicleClockMonitor::restart() {
  const std::uint64_t restarts = figures_.restarts + 1;
  figures_ = VehicleClockFigures{};
  figures_.restarts = restarts;
  minima_.clear();
  current_.reset();
  window_start_.reset();
  last_ts1_ns_.reset();
}

void VehicleClockMonitor::close_window() {
  if (!current_) return;
  minima_.push_back(*current_);
  current_.reset();
  if (minima_.size() > config_.windows_kept) minima_.erase(minima_.begin());
  fit();
}

void VehicleClockMonitor::fit() {
  figures_.windows = minima_.size();
  if (minima_.size() < std::max<std::size_t>(2, config_.windows_for_verdict)) return;
  // The line d = a + b·t through the minima, t in s from the first, d in ns: b is ns per s of host
  // time of (host − vehicle), so the vehicle's rate is −b ppb; the residual is the largest
  // |d − line|.
  std::vector<LinePoint> points;
  points.reserve(minima_.size());
  for (const Minimum& m : minima_) {
    points.push_back(
        {to_seconds(m.at - minima_.front().at),
         static_cast<double>(m.host_minus_vehicle_ns - minima_.front().host_minus_vehicle_ns)});
  }
  const std::optional<Line> line = fit_line(points);
  if (!line) return;
  const double b = line->slope;
  double residual_ns = 0;
  for (const LinePoint& p : points) {
    residual_ns = std::max(residual_ns, std::abs(p.y - line->at(p.x)));
  }
  figures_.rate_ppm = -b / 1e3;
  figures_.residual_ms = residual_ns / 1e6;
  const bool steady = std::abs(*figures_.rate_ppm) <= config_.max_rate_ppm &&
                      residual_ns <= static_cast<double>(config_.max_residual.count());
  // Unsteady once is unsteady until the vehicle restarts (the file comment says why).
  if (figures_.verdict != VehicleClockVerdict::unsteady) {
    figures_.verdict = steady ? VehicleClockVerdict::steady : VehicleClockVerdict::unsteady;
  }
}

}  // namespace mocaplink::core

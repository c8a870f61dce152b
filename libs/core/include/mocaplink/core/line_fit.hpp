// A least-squares straight line through points, for clock rates: the drift of a mocap source's
// clock (sender_clock.hpp) and of a vehicle's (vehicle_clock.hpp), both fitted to the minima of
// their windows. Pure.
#pragma once

#include <optional>
#include <span>

namespace mocaplink::core {

struct LinePoint {
  double x = 0;
  double y = 0;
};

/// y = intercept + slope · x.
struct Line {
  double intercept = 0;
  double slope = 0;
  [[nodiscard]] double at(double x) const noexcept { return intercept + slope * x; }
};

/// The least-squares line through `points`; nullopt for fewer than two distinct x. Callers pass
/// coordinates relative to their first point, which keeps the sums well conditioned.
[[nodiscard]] std::optional<Line> fit_line(std::span<const LinePoint> points) noexcept;

}  // namespace mocaplink::core

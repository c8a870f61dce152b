#include "mocaplink/core/line_fit.hpp"

namespace mocaplink::core {

std::optional<Line> fit_line(std::span<const LinePoint> points) noexcept {
  if (points.size() < 2) return std::nullopt;
  double sx = 0;
  double sy = 0;
  double sxx = 0;
  double sxy = 0;
  for (const LinePoint& p : points) {
    sx += p.x;
    sy += p.y;
    sxx += p.x * p.x;
    sxy += p.x * p.y;
  }
  const auto n = static_cast<double>(points.size());
  const double den = n * sxx - sx * sx;
  if (den <= 0) return std::nullopt;  // every point at one x: no slope to tell
  Line line;
  line.slope = (n * sxy - sx * sy) / den;
  line.intercept = (sy - line.slope * sx) / n;
  return line;
}

}  // namespace mocaplink::core

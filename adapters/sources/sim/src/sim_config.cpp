#include "mocaplink/sources/sim_config.hpp"

#include <string_view>

namespace mocaplink::sources {
namespace {

std::string range_error(std::string_view key, std::string_view range) {
  return "sim://: " + std::string(key) + " must be " + std::string(range);
}

}  // namespace

std::string validate_sim_config(const SimConfig& c) {
  if (c.bodies < 1 || c.bodies > 64) return range_error("bodies", "an integer in 1..64");
  if (!(c.rate_hz > 0.0 && c.rate_hz <= 2000.0)) return range_error("rate_hz", "in (0, 2000]");
  if (!(c.noise_mm >= 0.0 && c.noise_mm <= 1000.0)) return range_error("noise_mm", "in [0, 1000]");
  if (!(c.noise_deg >= 0.0 && c.noise_deg <= 90.0)) return range_error("noise_deg", "in [0, 90]");
  if (!(c.drop >= 0.0 && c.drop < 1.0)) return range_error("drop", "a probability in [0, 1)");
  if (!(c.occlude >= 0.0 && c.occlude <= 1.0)) return range_error("occlude", "in [0, 1]");
  if (!(c.occlude_s > 0.0 && c.occlude_s <= 60.0)) return range_error("occlude_s", "in (0, 60]");
  if (!(c.outliers >= 0.0 && c.outliers <= 1.0)) return range_error("outliers", "in [0, 1]");
  if (!(c.outlier_m > 0.0 && c.outlier_m <= 100.0)) return range_error("outlier_m", "in (0, 100]");
  return {};
}

}  // namespace mocaplink::sources

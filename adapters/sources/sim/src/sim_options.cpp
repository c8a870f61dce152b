#include "mocaplink/sources/sim_options.hpp"

#include <limits>
#include <optional>

namespace mocaplink::sources {
namespace {

/// The number options and their ranges: (low, high] or [low, high].
struct Number {
  std::string_view key;
  double SimOptions::*field;
  double low;
  double high;
  bool low_inclusive;
};
constexpr std::array<Number, 8> kNumbers{{
    {"rate_hz", &SimOptions::rate_hz, 0.0, 2000.0, false},
    {"noise_mm", &SimOptions::noise_mm, 0.0, 1000.0, true},
    {"noise_deg", &SimOptions::noise_deg, 0.0, 90.0, true},
    {"occlude", &SimOptions::occlude, 0.0, 1.0, true},
    {"occlude_s", &SimOptions::occlude_s, 0.0, 60.0, false},
    {"outliers", &SimOptions::outliers, 0.0, 1.0, true},
    {"outlier_m", &SimOptions::outlier_m, 0.0, 100.0, false},
    {"churn_s", &SimOptions::churn_s, 0.0, 3600.0, true},
}};
constexpr std::uint64_t kMaxCount = std::numeric_limits<std::int64_t>::max();

/// One option (the key is known: the registry checked it against kSimOptionKeys).
std::string read_option(std::string_view key, std::string_view value, SimOptions& sim) {
  for (const Number& n : kNumbers) {
    if (key == n.key) {
      return config::read_number_option(key, value, n.low, n.high, n.low_inclusive, sim.*n.field);
    }
  }
  std::uint64_t count = 0;
  std::string error;
  if (key == "drop") {
    // A probability below 1: at 1 no frame would ever arrive.
    double p = 0.0;
    if (!config::read_number_option(key, value, 0.0, 1.0, true, p).empty() || p >= 1.0) {
      return "drop must be a probability from 0 to below 1, got " + config::quote(value);
    }
    sim.drop = p;
  } else if (key == "bodies") {
    error = config::read_count_option(key, value, 1, 64, count);
    if (error.empty()) sim.bodies = static_cast<std::uint32_t>(count);
  } else if (key == "seed") {
    error = config::read_count_option(key, value, 0, kMaxCount, sim.seed);
  } else if (key == "frames") {
    error = config::read_count_option(key, value, 0, kMaxCount, sim.frames);
  }
  return error;
}

std::string range_error(std::string_view key, std::string_view range) {
  return "sim://: " + std::string(key) + " must be " + std::string(range);
}

}  // namespace

config::ValueOrError<SimOptions> parse_sim_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<SimOptions>;
  if (!url.body.empty() && url.body != "/") {
    return Result::failure("sim:// takes no host or path, only options, as in sim://?bodies=3");
  }
  SimOptions sim;
  for (const auto& [key, value] : url.query) {
    if (auto error = read_option(key, value, sim); !error.empty()) return Result::failure(error);
  }
  return sim;
}

std::string validate_sim_options(const SimOptions& c) {
  if (c.bodies < 1 || c.bodies > 64) return range_error("bodies", "an integer in 1..64");
  for (const Number& n : kNumbers) {
    const double v = c.*n.field;
    if (!((n.low_inclusive ? v >= n.low : v > n.low) && v <= n.high)) {
      return range_error(n.key, (n.low_inclusive ? "in [" : "in (") + config::format_number(n.low) +
                                    ", " + config::format_number(n.high) + "]");
    }
  }
  if (!(c.drop >= 0.0 && c.drop < 1.0)) return range_error("drop", "a probability in [0, 1)");
  return {};
}

}  // namespace mocaplink::sources

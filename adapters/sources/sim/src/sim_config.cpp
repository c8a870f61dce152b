#include "mocaplink/sources/sim_config.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace mocaplink::sources {
namespace {

/// Whole-string number (integer or floating point, no trailing characters, finite).
template <typename T>
bool parse_number(std::string_view text, T& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec != std::errc{} || ptr != end) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(out);
  return true;
}

/// Parses `value` into the member `Member` of `config`.
template <auto Member>
bool set(SimConfig& config, std::string_view value) {
  return parse_number(value, config.*Member);
}

struct Key {
  std::string_view name;
  bool (*set)(SimConfig&, std::string_view);
};

constexpr std::array<Key, 11> kKeys{{
    {"bodies", &set<&SimConfig::bodies>},
    {"rate_hz", &set<&SimConfig::rate_hz>},
    {"noise_mm", &set<&SimConfig::noise_mm>},
    {"noise_deg", &set<&SimConfig::noise_deg>},
    {"seed", &set<&SimConfig::seed>},
    {"drop", &set<&SimConfig::drop>},
    {"occlude", &set<&SimConfig::occlude>},
    {"occlude_s", &set<&SimConfig::occlude_s>},
    {"outliers", &set<&SimConfig::outliers>},
    {"outlier_m", &set<&SimConfig::outlier_m>},
    {"frames", &set<&SimConfig::frames>},
}};

std::string known_keys() {
  std::string out;
  for (const Key& key : kKeys) out += (out.empty() ? "" : ", ") + std::string(key.name);
  return out;
}

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

std::variant<SimConfig, std::string> sim_config_from_query(const UrlQuery& query) {
  SimConfig c;
  for (const auto& [key, value] : query) {
    const auto* known = std::find_if(kKeys.begin(), kKeys.end(),
                                     [&key = key](const Key& k) { return k.name == key; });
    if (known == kKeys.end()) {
      return "sim://: unknown key '" + key + "' (known: " + known_keys() + ")";
    }
    if (!known->set(c, value)) return "sim://: " + key + "='" + value + "' is not a number";
  }
  if (auto problem = validate_sim_config(c); !problem.empty()) return problem;
  return c;
}

}  // namespace mocaplink::sources

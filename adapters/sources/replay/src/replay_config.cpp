#include "mocaplink/sources/replay_config.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace mocaplink::sources {

std::variant<ReplayConfig, std::string> replay_config_from_url(std::string path,
                                                               const UrlQuery& query) {
  ReplayConfig config;
  config.path = std::move(path);
  if (config.path.empty()) return std::string("replay://: no file (want replay://FILE.csv)");
  for (const auto& [key, value] : query) {
    if (key == "speed") {
      const char* end = value.data() + value.size();
      const auto [ptr, ec] = std::from_chars(value.data(), end, config.speed);
      if (ec != std::errc{} || ptr != end || !(config.speed >= 0.0 && config.speed <= 1000.0)) {
        return "replay://: speed='" + value + "' must be a number in [0, 1000] (0 = as fast as " +
               "possible)";
      }
    } else if (key == "loop") {
      if (value != "0" && value != "1") return "replay://: loop='" + value + "' must be 0 or 1";
      config.loop = value == "1";
    } else {
      return "replay://: unknown key '" + key + "' (known: speed, loop)";
    }
  }
  return config;
}

core::Duration ReplaySchedule::due(core::SourceTime capture) {
  if (!first_capture_) first_capture_ = capture;
  if (speed_ <= 0.0) return core::Duration{0};
  const double since_first_ns = static_cast<double>((capture - *first_capture_).count()) / speed_;
  core::Duration due = pass_start_ + core::Duration{std::llround(std::max(0.0, since_first_ns))};
  if (due < last_due_) due = last_due_;  // never schedule backwards
  last_due_ = due;
  return due;
}

void ReplaySchedule::next_pass() {
  first_capture_.reset();
  pass_start_ = last_due_;
}

}  // namespace mocaplink::sources

#include "mocaplink/sources/replay_options.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace mocaplink::sources {

config::ValueOrError<ReplayOptions> parse_replay_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<ReplayOptions>;
  if (url.body.empty()) return Result::failure("replay:// needs a file, as in replay://flight.csv");
  ReplayOptions options;
  options.path = std::string(url.body);
  for (const auto& [key, value] : url.query) {
    if (key == "speed") {
      if (auto error = config::read_number_option(key, value, 0.0, 1000.0, true, options.speed);
          !error.empty()) {
        return Result::failure(error);
      }
    } else if (key == "loop") {
      if (value != "0" && value != "1") {
        return Result::failure("loop must be 0 or 1, got " + config::quote(value));
      }
      options.loop = value == "1";
    }
  }
  return options;
}

core::Duration ReplaySchedule::due(core::SourceTime capture) {
  if (!pass_started_) {
    first_capture_ = capture;
    pass_started_ = true;
  }
  if (speed_ <= 0.0) return core::Duration{0};
  const double since_first_ns = static_cast<double>((capture - first_capture_).count()) / speed_;
  core::Duration due = pass_start_ + core::Duration{std::llround(std::max(0.0, since_first_ns))};
  if (due < last_due_) due = last_due_;  // never schedule backwards
  last_due_ = due;
  return due;
}

void ReplaySchedule::next_pass() {
  pass_started_ = false;
  pass_start_ = last_due_;
}

}  // namespace mocaplink::sources

#include "mocaplink/core/sender_clock.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <span>

#include "mocaplink/core/line_fit.hpp"

namespace mocaplink::core {

namespace {
/// Complete windows in the drift fit (16 s at 2 s), and how many it needs.
constexpr std::size_t kDriftWindows = 8;
constexpr std::size_t kDriftMinWindows = 3;
}  // namespace

Duration CaptureTimeMapper::projected(const Minimum& m, HostTime t) const {
  const double ns = drift_ * static_cast<double>((t - m.seen).count());
  return m.candidate + Duration{static_cast<std::int64_t>(ns)};
}

void CaptureTimeMapper::fit_drift() {
  drift_ = 0;
  if (minima_.size() < kDriftMinWindows) return;
  // Candidate (ns) against receive time (ns), both from the first minimum.
  std::array<LinePoint, kDriftWindows> points{};
  for (std::size_t i = 0; i < minima_.size(); ++i) {
    points[i] = {static_cast<double>((minima_[i].seen - minima_.front().seen).count()),
                 static_cast<double>((minima_[i].candidate - minima_.front().candidate).count())};
  }
  if (const auto line = fit_line(std::span(points.data(), minima_.size()))) {
    drift_ = std::clamp(line->slope, -kMaxSourceDrift, kMaxSourceDrift);
  }
}

HostTime CaptureTimeMapper::on_frame(SourceTime capture, HostTime received,
                                     std::optional<Duration> latency) {
  // A negative or absurd reported latency is ignored rather than trusted (it comes from outside).
  Duration reported = latency.value_or(Duration::zero());
  if (reported < Duration::zero() || reported > config_.max_step) reported = Duration::zero();
  const Duration candidate = (received - reported).time_since_epoch() - capture.time_since_epoch();
  const Minimum sample{candidate, received};

  if (!offset_ || std::chrono::abs(candidate - *offset_) > config_.max_step) {
    // First frame, or the source clock jumped (restart): start again from this frame.
    if (offset_) ++reseeds_;
    current_min_ = sample;
    minima_.clear();
    drift_ = 0;
    window_start_ = received;
    last_result_.reset();
  } else if (received - window_start_ >= config_.window) {
    minima_.push_back(*current_min_);
    if (minima_.size() > kDriftWindows) minima_.erase(minima_.begin());
    fit_drift();
    current_min_ = sample;
    window_start_ = received;
  } else if (candidate < projected(*current_min_, received)) {
    current_min_ = sample;
  }
  offset_ = projected(*current_min_, received);
  // The previous window's minimum is the latest complete one.
  if (!minima_.empty()) offset_ = std::min(*offset_, projected(minima_.back(), received));

  HostTime result = HostTime{capture.time_since_epoch() + *offset_};
  // Never in the future (offset ≤ this frame's candidate guarantees it up to a dropped latency),
  // and strictly increasing so that the vehicles' filters never see time go backwards.
  result = std::min(result, received);
  if (last_result_ && result <= *last_result_)
    result = *last_result_ + std::chrono::microseconds(1);
  last_result_ = result;
  return result;
}

std::optional<HostTime> CaptureTimeMapper::to_host(SourceTime capture) const {
  if (!offset_) return std::nullopt;
  return HostTime{capture.time_since_epoch() + *offset_};
}

std::uint64_t host_time_usec(HostTime t) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch());
  return us.count() < 0 ? 0 : static_cast<std::uint64_t>(us.count());
}

std::optional<GpsTime> gps_time_from_unix_us(std::int64_t unix_us) {
  constexpr std::int64_t kWeekUs = std::int64_t{604'800} * 1'000'000;
  const std::int64_t gps_us = unix_us - (kGpsEpochUnixS - kGpsLeapSeconds) * 1'000'000;
  if (gps_us < 0) return std::nullopt;
  const std::int64_t week = gps_us / kWeekUs;
  if (week > 0xFFFF) return std::nullopt;
  GpsTime t;
  t.week = static_cast<std::uint16_t>(week);
  t.week_ms = static_cast<std::uint32_t>((gps_us % kWeekUs) / 1000);
  return t;
}

}  // namespace mocaplink::core

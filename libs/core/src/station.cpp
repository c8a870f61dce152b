#include "mocaplink/core/station.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mocaplink::core {

Station::Station(StationConfig config) : config_(config) {}

void Station::on_connection(bool connected) {
  connected_ = connected;
  if (!connected) continuity_ = false;
}

void Station::count_frame_number(std::uint64_t n, std::uint32_t step) {
  if (step == 0) {
    totals_.drops_counted = false;
  } else if (continuity_ && totals_.last_frame_number) {
    const std::uint64_t last = *totals_.last_frame_number;
    if (n == last) {
      ++totals_.duplicates;
    } else if (n < last || n - last - 1 > config_.max_gap_frames) {
      ++totals_.restarts;
    } else {
      totals_.dropped += (n - last) / step - (n - last >= step ? 1 : 0);
    }
  }
  totals_.last_frame_number = n;
  continuity_ = true;
}

void Station::update_bodies(const MocapFrame& frame, HostTime received) {
  for (auto& body : totals_.bodies) {  // absent from this frame: untracked
    body.tracked = false;
    body.mirrored = false;
  }
  for (const auto& sample : frame.bodies) {
    auto it = body_index_.find(sample.name);
    if (it == body_index_.end()) {
      if (totals_.bodies.size() >= config_.max_bodies) {
        ++totals_.bodies_ignored;
        continue;
      }
      it = body_index_.emplace(sample.name, totals_.bodies.size()).first;
      StationBody fresh;
      fresh.name = sample.name;
      totals_.bodies.push_back(std::move(fresh));
    }
    StationBody& body = totals_.bodies[it->second];
    body.tracked = sample.tracked;
    body.mirrored = !sample.tracked && sample.mirrored;
    if (!sample.tracked) continue;
    body.ever_tracked = true;
    body.p_world_m = sample.p_world_m;
    body.q_world_body = sample.q_world_body;
    ++body.frames_tracked;
    body.last_tracked = received;
  }
}

void Station::on_frame(const MocapFrame& frame, HostTime received) {
  connected_ = true;
  ++totals_.frames;
  count_frame_number(frame.frame_number, frame.frame_step);
  if (frame.frame_rate_hz) totals_.nominal_rate_hz = frame.frame_rate_hz;
  totals_.last_received = received;
  update_bodies(frame, received);

  window_.push_back(Arrival{received,
                            received.time_since_epoch() - frame.capture_time.time_since_epoch(),
                            frame.source_latency});
  while (window_.size() > config_.max_window_frames ||
         (!window_.empty() && window_.front().received <= received - config_.window)) {
    window_.pop_front();
  }
}

StationSnapshot Station::snapshot(HostTime now) const {
  StationSnapshot out = totals_;
  out.connected = connected_;
  std::size_t n = 0;
  std::optional<HostTime> oldest;
  double latency_sum_ms = 0.0;
  std::size_t latency_count = 0;
  // Offsets are shifted by the first one before summing: raw offsets are huge (the two clocks'
  // epochs differ by days) and their squares would cancel catastrophically.
  std::optional<Duration> shift;
  double offset_sum_ms = 0.0;
  double offset_sum_sq_ms2 = 0.0;
  for (std::size_t i = 0; i < window_.size(); ++i) {
    const Arrival& a = window_[i];
    if (a.received <= now - config_.window || a.received > now) continue;
    ++n;
    if (!oldest) oldest = a.received;
    if (a.latency) {
      latency_sum_ms += to_seconds(*a.latency) * 1e3;
      ++latency_count;
    }
    if (!shift) shift = a.receive_minus_capture;
    const double offset_ms = to_seconds(a.receive_minus_capture - *shift) * 1e3;
    offset_sum_ms += offset_ms;
    offset_sum_sq_ms2 += offset_ms * offset_ms;
  }
  if (n >= 2 && now > *oldest) {
    out.frame_rate_hz = static_cast<double>(n - 1) / to_seconds(now - *oldest);
  }
  if (latency_count > 0) out.latency_ms = latency_sum_ms / static_cast<double>(latency_count);
  if (n >= 2) {
    const double mean = offset_sum_ms / static_cast<double>(n);
    const double variance = offset_sum_sq_ms2 / static_cast<double>(n) - mean * mean;
    out.jitter_ms = std::sqrt(std::max(0.0, variance));
  }
  return out;
}

}  // namespace mocaplink::core

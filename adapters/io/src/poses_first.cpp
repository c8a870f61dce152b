#include "mocaplink/io/poses_first.hpp"

#include <algorithm>

namespace mocaplink::io {

PosesFirst::PosesFirst(Options options) : options_(options) {}

std::chrono::nanoseconds PosesFirst::air_time(std::size_t bytes) const {
  if (options_.bytes_per_second <= 0.0) return std::chrono::nanoseconds{0};
  return std::chrono::nanoseconds(
      static_cast<std::int64_t>(static_cast<double>(bytes) * 1e9 / options_.bytes_per_second));
}

void PosesFirst::occupy(std::size_t bytes, core::HostTime now) {
  // At most a full queue's air time ahead: a link that takes bytes faster than its nominal speed
  // (a pty, USB serial) would otherwise let the model run ahead of the wire without bound.
  busy_until_ =
      std::min(std::max(busy_until_, now) + air_time(bytes), now + air_time(kModelCapBytes));
}

void PosesFirst::observe_unsent(std::size_t bytes, core::HostTime now) {
  // Only ever later: a pty (or a USB serial port) says 0 while the line behind it is still busy.
  if (options_.bytes_per_second > 0.0) busy_until_ = std::max(busy_until_, now + air_time(bytes));
}

void PosesFirst::on_own_write(std::size_t bytes, core::HostTime now) {
  counters_.own_bytes += bytes;
  last_own_ = now;
  occupy(bytes, now);
}

bool PosesFirst::push(std::span<const std::uint8_t> frame, core::HostTime now) {
  if (queued_bytes_ + frame.size() > options_.max_queue_bytes) {
    ++counters_.dropped_full;
    return false;
  }
  queue_.push_back(Waiting{std::vector<std::uint8_t>(frame.begin(), frame.end()), now});
  queued_bytes_ += frame.size();
  ++counters_.queued;
  return true;
}

std::optional<std::vector<std::uint8_t>> PosesFirst::next(core::HostTime now,
                                                          core::HostTime& retry_at) {
  while (!queue_.empty() && now - queue_.front().since > options_.max_age) {
    queued_bytes_ -= queue_.front().frame.size();
    queue_.pop_front();
    ++counters_.dropped_stale;
  }
  if (queue_.empty()) return std::nullopt;
  const std::vector<std::uint8_t>& frame = queue_.front().frame;
  if (options_.bytes_per_second > 0.0 && pose_period_.count() > 0 && last_own_) {
    const core::HostTime due = *last_own_ + pose_period_ - pose_period_ / 10;
    const bool poses_flowing = now - *last_own_ < pose_period_ * 3 / 2;
    const core::HostTime done = std::max(busy_until_, now) + air_time(frame.size());
    if (poses_flowing && done > due) {
      // After the next pose has gone (or when it is overdue).
      retry_at = std::max(due + pose_period_ / 10, now + std::chrono::milliseconds(1));
      return std::nullopt;
    }
  }
  std::vector<std::uint8_t> out = std::move(queue_.front().frame);
  queue_.pop_front();
  queued_bytes_ -= out.size();
  ++counters_.handed_out;
  counters_.bytes_handed_out += out.size();
  occupy(out.size(), now);
  return out;
}

std::uint64_t PosesFirst::clear() noexcept {
  const std::uint64_t n = queue_.size();
  queue_.clear();
  queued_bytes_ = 0;
  return n;
}

}  // namespace mocaplink::io

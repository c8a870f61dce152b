#include "mocaplink/io/link_backlog.hpp"

#include <cassert>
#include <utility>

namespace mocaplink::io {

bool LinkBacklog::append(std::span<const std::uint8_t> frame) {
  if (bytes() + frame.size() > max_bytes_) return false;
  pending_.insert(pending_.end(), frame.begin(), frame.end());
  ++pending_frames_;
  return true;
}

std::span<const std::uint8_t> LinkBacklog::begin_write() {
  assert(!writing_ && !pending_.empty());
  std::swap(pending_, in_flight_);
  pending_.clear();
  in_flight_frames_ = pending_frames_;
  pending_frames_ = 0;
  writing_ = true;
  return in_flight_;
}

std::uint64_t LinkBacklog::finish_write() noexcept {
  const std::uint64_t frames = in_flight_frames_;
  in_flight_.clear();
  in_flight_frames_ = 0;
  writing_ = false;
  return frames;
}

std::uint64_t LinkBacklog::clear() noexcept {
  const std::uint64_t frames = pending_frames_ + in_flight_frames_;
  pending_.clear();
  in_flight_.clear();
  pending_frames_ = in_flight_frames_ = 0;
  writing_ = false;
  return frames;
}

}  // namespace mocaplink::io

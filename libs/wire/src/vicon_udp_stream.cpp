#include "mocaplink/wire/vicon_udp_stream.hpp"

#include <algorithm>
#include <bit>

namespace mocaplink::wire::vicon_udp {

core::SourceTime Stream::capture_at(core::HostTime host, std::int64_t frames_since_last) {
  std::optional<core::Duration> step;
  if (last_arrival_ && frames_since_last > 0) {
    // The frame period: the median of the recent arrival gaps per frame number, which a burst
    // (some gaps near 0, one long) does not move.
    gaps_.push_back((host - *last_arrival_) / frames_since_last);
    if (gaps_.size() > kPeriodSamples) gaps_.pop_front();
    if (gaps_.size() >= 3) {
      std::vector<core::Duration> sorted(gaps_.begin(), gaps_.end());
      std::nth_element(sorted.begin(),
                       sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                       sorted.end());
      step = sorted[sorted.size() / 2] * frames_since_last;
    }
  } else {
    gaps_.clear();  // a new start: the period is measured again
  }
  last_arrival_ = host;
  return clock_.next(host, step);
}

core::BodySample Stream::sample(const Object& o) {
  core::BodySample s;
  s.name = o.name;
  s.p_world_m = o.t_mm / 1000.0;
  s.q_world_body = to_quaternion(o.rot_rad, config_.rotation);
  s.tracked = !o.all_zero();
  const std::array<double, 6> values{o.t_mm.x(),    o.t_mm.y(),    o.t_mm.z(),
                                     o.rot_rad.x(), o.rot_rad.y(), o.rot_rad.z()};
  auto it = seen_.find(o.name);
  if (it == seen_.end() && seen_.size() < kMaxObjects) {
    it = seen_.emplace(o.name, Seen{values, 0}).first;
    names_.push_back(o.name);
  } else if (it != seen_.end()) {
    // Bit-identical, not merely equal: a tracked body's doubles never hold still.
    const bool same =
        std::equal(values.begin(), values.end(), it->second.values.begin(), [](double a, double b) {
          return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
        });
    it->second.repeats = same ? it->second.repeats + 1 : 0;
    it->second.values = values;
    if (config_.frozen > 0 && it->second.repeats > config_.frozen) s.tracked = false;
  }
  if (!s.tracked) ++counters_.untracked;
  return s;
}

Result<std::optional<core::MocapFrame>> Stream::on_datagram(std::span<const std::byte> bytes,
                                                            core::HostTime arrival) {
  ++counters_.datagrams;
  auto parsed = parse_datagram(bytes, config_.max_abs_mm);
  if (!parsed) {
    ++counters_.malformed;
    return parsed.error();
  }
  const Datagram& d = parsed.value();
  counters_.unknown_items += d.unknown_items;
  if (d.padding_bytes > 0) ++counters_.padded;
  std::int64_t advanced = 0;  // frame numbers since the last datagram; 0: a new start
  lost_sent_ = false;
  if (last_raw_) {
    const std::int64_t diff = frame_difference(d.frame, *last_raw_);
    if (diff == 0 && current_) {
      // The rest of a frame split over datagrams: the frame again, with these objects added.
      ++counters_.split_frames;
      for (const Object& o : d.objects) {
        auto s = sample(o);
        auto& bodies = current_->bodies;
        auto same = std::find_if(bodies.begin(), bodies.end(),
                                 [&](const core::BodySample& b) { return b.name == s.name; });
        if (same != bodies.end()) {
          *same = std::move(s);
        } else {
          bodies.push_back(std::move(s));
        }
      }
      return std::optional<core::MocapFrame>(*current_);
    }
    if (diff <= 0 && -diff <= kMaxLateFrames) {  // older, or a repeat after a silence
      ++counters_.late;
      return std::optional<core::MocapFrame>();
    }
    if (diff > 0) {
      advanced = diff;
      if (d.frame < *last_raw_) ++counters_.wraps;
      const auto step = static_cast<std::uint32_t>(diff);
      if (step_ == 0 || step < step_) step_ = step;
      if (step > step_) ++counters_.gaps;
      unwrapped_ += static_cast<std::uint64_t>(diff);
    } else {
      ++counters_.restarts;
      unwrapped_ = d.frame;
    }
  } else {
    unwrapped_ = d.frame;
  }
  last_raw_ = d.frame;
  core::MocapFrame frame;
  frame.frame_number = unwrapped_;
  frame.frame_step = step_ == 0 ? 1 : step_;
  frame.capture_time = capture_at(arrival, advanced);
  for (const Object& o : d.objects) frame.bodies.push_back(sample(o));
  current_ = frame;
  return std::optional<core::MocapFrame>(std::move(frame));
}

std::optional<core::MocapFrame> Stream::on_silence(core::HostTime now) {
  if (lost_sent_ || !current_) return std::nullopt;
  lost_sent_ = true;
  core::MocapFrame frame;
  frame.frame_number = current_->frame_number;
  frame.frame_step = current_->frame_step;
  frame.capture_time = clock_.next(now, std::nullopt);
  last_arrival_.reset();  // the period is measured again when the stream resumes
  for (const auto& name : names_) {
    core::BodySample s;
    s.name = name;
    frame.bodies.push_back(std::move(s));
  }
  // Whatever comes next starts afresh: no frozen count or split frame spans the silence.
  current_.reset();
  for (auto& [name, seen] : seen_) seen.repeats = 0;
  return frame;
}

}  // namespace mocaplink::wire::vicon_udp

#include "mocaplink/wire/vicon_served_frame.hpp"

#include <chrono>
#include <cmath>

#include "mocaplink/wire/vicon_pose.hpp"

namespace mocaplink::wire::vicon {

std::int64_t frame_period_ticks(double rate_hz) {
  return static_cast<std::int64_t>(std::llround(kStreamClockHz / rate_hz));
}

ServedFrame ServedFrameBuilder::build(const core::MocapFrame& frame, std::int64_t period_ticks) {
  for (ServedSubject& s : subjects_) s.tracked = false;
  for (const core::BodySample& body : frame.bodies) {
    auto [it, inserted] = index_by_name_.try_emplace(body.name, subjects_.size());
    if (inserted) {
      ServedSubject s;
      s.subject_id = static_cast<std::uint32_t>(subjects_.size() + 1);
      s.name = body.name;
      subjects_.push_back(std::move(s));
    }
    ServedSubject& s = subjects_[it->second];
    s.tracked = body.tracked;
    if (body.tracked) {
      const Eigen::Vector3d mm = body.p_world_m * 1000.0;
      s.translation_mm = {mm.x(), mm.y(), mm.z()};
      s.rotation = rotation_from_quaternion(body.q_world_body);
    }
  }
  ServedFrame out;
  out.sequence = ++sequence_;
  const auto id = static_cast<std::uint32_t>(frame.frame_number & 0xFFFFFFFFu);
  out.frame_id = id == kInvalidFrameId ? 0 : id;
  out.frame_period_ticks = period_ticks;
  out.subjects = subjects_;
  if (frame.source_latency) {
    out.latency.push_back(LatencySample{
        "Emulator Acquisition", std::chrono::duration<double>(*frame.source_latency).count()});
  }
  return out;
}

}  // namespace mocaplink::wire::vicon

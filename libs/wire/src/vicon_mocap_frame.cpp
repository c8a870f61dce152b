#include "mocaplink/wire/vicon_mocap_frame.hpp"

#include <chrono>
#include <cmath>

#include "mocaplink/wire/vicon_pose.hpp"

namespace mocaplink::wire::vicon {

namespace {

// frame_id × period ticks of 135 MHz in ns, without overflow for any u32 id and period <= 1e12:
// 1 tick = 200/27 ns.
core::SourceTime capture_time(std::uint32_t frame_id, std::int64_t period_ticks) {
  const long double ticks =
      static_cast<long double>(frame_id) * static_cast<long double>(period_ticks);
  const long double ns = ticks * 200.0L / 27.0L;
  return core::source_time_from_ns(static_cast<std::int64_t>(std::llround(ns)));
}

}  // namespace

MappedFrame to_mocap_frame(const DecodedFrame& decoded) {
  MappedFrame out;
  core::MocapFrame& f = out.frame;
  f.frame_number = decoded.frame_id;
  // Periods above ~2 hours per frame are nonsense; keep the rate unknown rather than overflow.
  if (decoded.frame_period_ticks && *decoded.frame_period_ticks <= 1'000'000'000'000) {
    f.frame_rate_hz = kStreamClockHz / static_cast<double>(*decoded.frame_period_ticks);
    f.capture_time = capture_time(decoded.frame_id, *decoded.frame_period_ticks);
  }
  if (decoded.latency) {
    double total_s = 0.0;
    for (const LatencySample& s : decoded.latency->samples) total_s += s.seconds;
    if (std::isfinite(total_s) && std::abs(total_s) < 3600.0) {
      f.source_latency = std::chrono::round<core::Duration>(std::chrono::duration<double>(total_s));
    }
  }
  f.bodies.reserve(decoded.subjects.size());
  for (const SubjectSample& s : decoded.subjects) {
    core::BodySample body;
    body.name = s.name;
    if (!s.occluded) {
      const Eigen::Vector3d t_mm(s.translation_mm[0], s.translation_mm[1], s.translation_mm[2]);
      const auto q = quaternion_from_rotation(s.rotation);
      if (q && t_mm.allFinite()) {
        body.tracked = true;
        body.p_world_m = (decoded.y_up ? y_up_to_z_up(t_mm) : t_mm) / 1000.0;
        body.q_world_body = decoded.y_up ? y_up_to_z_up(*q) : *q;
      } else {
        ++out.invalid_poses;
        body.mirrored = is_mirrored_rotation(s.rotation);
      }
    }
    f.bodies.push_back(std::move(body));
  }
  return out;
}

}  // namespace mocaplink::wire::vicon

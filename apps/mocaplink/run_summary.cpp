#include "run_summary.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace mocaplink::app {
namespace {

/// Pose/GPS messages sent so far: the count of the most-sent kind (one per due send).
std::uint64_t poses_sent(const core::SenderCounters& c) {
  return *std::max_element(c.sent.begin(), c.sent.end());
}

std::uint64_t rejected(const mavlink::ParserCounters& p) {
  return p.bad_crc + p.unknown_incompat + p.bad_signature + p.replay + p.stale_new_stream +
         p.unsigned_rejected + p.too_many_streams + p.truncated_tail;
}

std::string vehicle_state(const core::VehicleStatus& v) {
  std::string out = fmt::format("vehicle {}", core::to_string(v.vehicle.link));
  if (v.vehicle.origin != core::OriginState::not_needed) {
    out += fmt::format(", origin {}", core::to_string(v.vehicle.origin));
  }
  if (v.vehicle.timesync) {
    out += fmt::format(", timesync offset {:.3f} ms rtt {:.3f} ms ({} samples)",
                       static_cast<double>(v.vehicle.timesync->offset_ns) / 1e6,
                       static_cast<double>(v.vehicle.timesync->rtt_ns) / 1e6,
                       v.vehicle.timesync->samples);
  }
  return out;
}

}  // namespace

Summary::Summary(const config::Config& config, std::chrono::milliseconds period)
    : config_(config), period_(period) {}

void Summary::describe_vehicle(const config::Vehicle& v, const io::Link& link) const {
  spdlog::info("vehicle {}: body {} -> {} as system {} component {}, profile {}, {:g} Hz{}{}",
               v.spec.name, v.spec.body, link.url(), v.spec.system_id, v.spec.component_id,
               core::to_string(v.spec.profile), v.spec.rate_hz,
               v.spec.signing_key ? ", signed" : "", v.spec.enabled ? "" : ", disabled");
}

void Summary::on_event(const core::BridgeEvent& event, core::HostTime now) {
  auto& limit = limits_[std::string(core::to_string(event.kind)) + "/" + event.subject];
  if (limit.last != core::HostTime{} && now - limit.last < std::chrono::seconds(1)) {
    ++limit.suppressed;
    return;
  }
  const std::string suppressed =
      limit.suppressed > 0 ? fmt::format(" ({} similar suppressed)", limit.suppressed) : "";
  limit = Limit{now, 0};
  const bool bad = event.kind == core::BridgeEventKind::body_lost ||
                   (event.kind == core::BridgeEventKind::agreement &&
                    event.text.find("disagree") != std::string::npos) ||
                   (event.kind == core::BridgeEventKind::origin_state &&
                    event.text.find("conflict") != std::string::npos);
  const auto level = bad ? spdlog::level::warn : spdlog::level::info;
  spdlog::log(level, "{} {}: {}{}", core::to_string(event.kind), event.subject, event.text,
              suppressed);
}

void Summary::log(const core::BridgeSnapshot& snapshot, const std::vector<VehicleLink>& links,
                  std::uint64_t queue_overflows, std::uint64_t late_frames, bool final) {
  const double dt = previous_time_ ? core::to_seconds(snapshot.time - *previous_time_)
                                   : std::chrono::duration<double>(period_).count();
  previous_time_ = snapshot.time;
  // Rate limits of subjects quiet for a minute are forgotten: vehicles and bodies come and go
  // (dashboard), and the map must not grow with every name ever seen.
  std::erase_if(limits_, [&](const auto& entry) {
    return snapshot.time - entry.second.last > std::chrono::minutes(1);
  });
  const auto& st = snapshot.station;
  spdlog::info(
      "{}source {}: {}, {} frames ({:.1f} Hz), {} dropped, {} queue overflows, {} late frames "
      "skipped",
      final ? "final: " : "", config_.mocap.source.text,
      st.connected ? "connected" : "not connected", st.frames, st.frame_rate_hz,
      st.drops_counted ? std::to_string(st.dropped) : std::string("n/a"), queue_overflows,
      late_frames);
  const bool detailed = snapshot.vehicles.size() <= kDetailedVehicles;
  std::map<std::string, Previous> next;  // only live vehicles: removed ones are forgotten
  double min_hz = 0.0;
  double max_hz = 0.0;
  std::uint64_t total_sent = 0;
  std::uint64_t total_dropped = 0;
  std::uint64_t total_errors = 0;
  bool first = true;
  for (const auto& v : snapshot.vehicles) {
    if (v.index >= links.size() || !links[v.index].link) continue;
    const io::Link& link = *links[v.index].link;
    const auto c = link.counters();
    const std::uint64_t poses = poses_sent(v.sender.counters);
    // A vehicle added since the last summary (or removed and added again) counts from zero.
    const auto before = previous_.find(v.name);
    const std::uint64_t poses_before =
        before != previous_.end() && before->second.poses <= poses ? before->second.poses : 0;
    const double pose_hz = dt > 0 ? static_cast<double>(poses - poses_before) / dt : 0.0;
    next[v.name] = Previous{poses, c.frames_sent};
    const std::uint64_t dropped = c.dropped_down + c.dropped_backlog;
    const std::uint64_t errors = c.send_errors + c.receive_errors;
    min_hz = first ? pose_hz : std::min(min_hz, pose_hz);
    first = false;
    max_hz = std::max(max_hz, pose_hz);
    total_sent += c.frames_sent;
    total_dropped += dropped;
    total_errors += errors;
    const bool problem = dropped > 0 || errors > 0 || rejected(c.parser) > 0;
    if (!detailed && !problem && !final) continue;
    spdlog::log(problem ? spdlog::level::warn : spdlog::level::info,
                "{}vehicle {}: {:.1f} Hz poses ({} total), link {} {}: {} frames sent, {} "
                "dropped, {} errors, {} refused; {} frames received, {} rejected; {}",
                final ? "final: " : "", v.name, pose_hz, poses, link.url(),
                io::to_string(link.state()), c.frames_sent, dropped, errors, c.refused,
                c.parser.frames, rejected(c.parser), vehicle_state(v));
  }
  if (!detailed) {
    spdlog::info(
        "{}vehicles: {}, pose rate {:.1f}..{:.1f} Hz, {} frames sent, {} dropped, {} "
        "errors",
        final ? "final: " : "", snapshot.vehicles.size(), min_hz, max_hz, total_sent, total_dropped,
        total_errors);
  }
  previous_ = std::move(next);
}

}  // namespace mocaplink::app

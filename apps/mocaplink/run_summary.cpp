#include "run_summary.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "mocaplink/core/rate_window.hpp"

namespace mocaplink::app {
namespace {

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

void Summary::describe_vehicle(const config::Vehicle& v, const io::Link& link, core::HostTime now) {
  started_[v.spec.name] = now;
  spdlog::info("vehicle {}: body {} -> {} as system {} component {}, profile {}, {:g} Hz{}{}",
               v.spec.name, v.spec.body, link.url(), v.spec.system_id, v.spec.component_id,
               core::to_string(v.spec.profile), v.spec.rate_hz,
               v.spec.signing_key ? ", signed" : "", v.spec.enabled ? "" : ", disabled");
}

void Summary::on_event(const core::BridgeEvent& event, core::HostTime now) {
  // What was asked of a vehicle, and its set-up, come a few lines per boot of the vehicle, never
  // per retry (core::VehicleStreams, core::VehicleSetup, which also logs a repeated STATUSTEXT
  // once per 30 s), and each says something different: all are logged.
  if (event.kind == core::BridgeEventKind::vehicle_streams ||
      event.kind == core::BridgeEventKind::vehicle_setup) {
    write(event, 0);
    return;
  }
  if (const auto now_logged = limiter_.offer(event, now)) {
    write(now_logged->event, now_logged->suppressed);
  }
}

void Summary::flush(core::HostTime now, bool all) {
  for (const core::LimitedEvent& held : limiter_.flush(now, all))
    write(held.event, held.suppressed);
}

void Summary::write(const core::BridgeEvent& event, std::uint64_t suppressed) {
  const auto has = [&](std::string_view word) {
    return event.text.find(word) != std::string::npos;
  };
  const bool bad =
      event.kind == core::BridgeEventKind::body_lost ||
      event.kind == core::BridgeEventKind::body_mirrored ||
      (event.kind == core::BridgeEventKind::agreement && has("disagree")) ||
      (event.kind == core::BridgeEventKind::origin_state &&
       (has("conflict") || has("unconfirmed"))) ||
      (event.kind == core::BridgeEventKind::vehicle_setup &&
       (has("set-up blocked") || has("set-up no answer") || has("the vehicle kept") ||
        has("never confirmed") || has("vehicle says (error)") || has("vehicle says (critical)") ||
        has("vehicle says (alert)") || has("vehicle says (emergency)"))) ||
      (event.kind == core::BridgeEventKind::vehicle_clock && has("no longer answered")) ||
      (event.kind == core::BridgeEventKind::vehicle_streams &&
       (has("no ATTITUDE") || has("no LOCAL_POSITION_NED") || has("not asked again")));
  const auto level = bad ? spdlog::level::warn : spdlog::level::info;
  spdlog::log(level, "{} {}: {}{}", core::to_string(event.kind), event.subject, event.text,
              suppressed > 0 ? fmt::format(" ({} similar suppressed)", suppressed) : "");
}

void Summary::log(const core::BridgeSnapshot& snapshot, const std::vector<VehicleLink>& links,
                  std::uint64_t queue_overflows, std::uint64_t late_frames,
                  std::uint64_t superseded_frames, bool final) {
  const double dt = previous_time_ ? core::to_seconds(snapshot.time - *previous_time_)
                                   : std::chrono::duration<double>(period_).count();
  previous_time_ = snapshot.time;
  // Rate limits of subjects quiet for a minute are forgotten: vehicles and bodies come and go
  // (dashboard), and the map must not grow with every name ever seen.
  limiter_.forget_quiet(snapshot.time, std::chrono::minutes(1));
  const auto& st = snapshot.station;
  // Periodic: the Station's rate over its last second. Final: the whole run's average.
  const core::HostTime run_start = begun_.value_or(snapshot.time);
  const std::string source_rate =
      final ? fmt::format("{:.1f} Hz on average over the run's {:.1f} s",
                          core::average_rate_hz(st.frames, snapshot.time - run_start),
                          core::to_seconds(snapshot.time - run_start))
            : fmt::format("{:.1f} Hz", st.frame_rate_hz);
  spdlog::info(
      "{}source {}: {}, {} frames ({}), {} dropped, {} queue overflows, {} late frames skipped, "
      "{} frames superseded",
      final ? "final: " : "", config_.mocap.source.text,
      st.connected ? "connected" : "not connected", st.frames, source_rate,
      st.drops_counted ? std::to_string(st.dropped) : std::string("n/a"), queue_overflows,
      late_frames, superseded_frames);
  const bool detailed = snapshot.vehicles.size() <= kDetailedVehicles;
  std::map<std::string, Previous> next;  // only live vehicles: removed ones are forgotten
  std::map<std::string, core::HostTime> started;
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
    const std::uint64_t poses = v.sender.counters.poses;
    // Final: poses over the time since the vehicle started (the run, or since it was added).
    const auto since = started_.find(v.name);
    const core::HostTime vehicle_start = since != started_.end() ? since->second : run_start;
    started[v.name] = vehicle_start;
    // Periodic: over the period. A vehicle added since the last summary (or removed and added
    // again) counts from zero.
    const auto before = previous_.find(v.name);
    const std::uint64_t poses_before =
        before != previous_.end() && before->second.poses <= poses ? before->second.poses : 0;
    const double pose_hz = final ? core::average_rate_hz(poses, snapshot.time - vehicle_start)
                                 : (dt > 0 ? static_cast<double>(poses - poses_before) / dt : 0.0);
    const double lived_s = core::to_seconds(snapshot.time - vehicle_start);
    std::string pose_rate = fmt::format("{:.1f} Hz poses over the last {:.0f} s", pose_hz, dt);
    if (final && vehicle_start == run_start) {
      pose_rate =
          fmt::format("{:.1f} Hz poses on average over the run's {:.1f} s", pose_hz, lived_s);
    } else if (final) {
      pose_rate = fmt::format("{:.1f} Hz poses on average over the {:.1f} s since it was added",
                              pose_hz, lived_s);
    }
    const std::uint64_t dropped = c.dropped_down + c.dropped_backlog;
    const std::uint64_t errors = c.send_errors + c.receive_errors;
    const std::uint64_t trouble = dropped + errors + rejected(c.parser);
    next[v.name] = Previous{poses, trouble};
    min_hz = first ? pose_hz : std::min(min_hz, pose_hz);
    first = false;
    max_hz = std::max(max_hz, pose_hz);
    total_sent += c.frames_sent;
    total_dropped += dropped;
    total_errors += errors;
    // A warning when something was dropped, failed or rejected in this period (or ever, in the
    // final line): three frames dropped at start-up do not make every later line a warning.
    const std::uint64_t trouble_before =
        before != previous_.end() && before->second.trouble <= trouble ? before->second.trouble : 0;
    const bool problem = final ? trouble > 0 : trouble > trouble_before;
    if (!detailed && !problem && !final) continue;
    spdlog::log(problem ? spdlog::level::warn : spdlog::level::info,
                "{}vehicle {}: {} ({} total), link {} {}: {} frames sent, {} dropped, {} "
                "errors, {} refused; {} frames received, {} rejected; {}",
                final ? "final: " : "", v.name, pose_rate, poses, link.url(),
                io::to_string(link.state()), c.frames_sent, dropped, errors, c.refused,
                c.parser.frames, rejected(c.parser), vehicle_state(v));
  }
  if (!detailed) {
    spdlog::info(
        "{}vehicles: {}, pose rate {:.1f}..{:.1f} Hz{}, {} frames sent, {} dropped, {} errors",
        final ? "final: " : "", snapshot.vehicles.size(), min_hz, max_hz,
        final ? " on average over the run" : fmt::format(" over the last {:.0f} s", dt), total_sent,
        total_dropped, total_errors);
  }
  previous_ = std::move(next);
  started_ = std::move(started);
}

}  // namespace mocaplink::app

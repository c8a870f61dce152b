#include "mocaplink/web/alerts.hpp"

#include <algorithm>
#include <string>

namespace mocaplink::web {

AlertMonitor::AlertMonitor(AlertRules rules) : rules_(rules) {}

void AlertMonitor::annotate(StatusView& status, double now_s) {
  auto add = [&status](AlertLevel level, std::string kind, std::string subject,
                       std::string message) {
    status.alerts.push_back(Alert{level, std::move(kind), std::move(subject), std::move(message)});
  };
  const StationView& station = status.station;
  if (!station.connected) {
    add(AlertLevel::error, "source_disconnected", "station",
        "No frames from " + station.source +
            (station.error.empty() ? std::string() : ": " + station.error));
  }
  for (const BodyView& body : station.bodies) {
    const bool followed = std::any_of(status.vehicles.begin(), status.vehicles.end(),
                                      [&](const VehicleView& v) { return v.body == body.name; });
    if (body.mirrored) {
      add(followed ? AlertLevel::error : AlertLevel::warning, "body_mirrored", body.name,
          body.name +
              "'s rotation from the source is mirrored (left-handed): no axis setting can fix "
              "it; check the handedness of the mocap system's frame");
    }
    if (body.state != core::TrackingState::lost) continue;
    add(followed ? AlertLevel::error : AlertLevel::warning, "body_lost", body.name,
        body.name + " is lost" + (followed ? ": its vehicle gets no pose" : ""));
  }
  for (const VehicleView& vehicle : status.vehicles) {
    if (vehicle.link_state == LinkHealth::down) {
      add(AlertLevel::error, "link_down", vehicle.name,
          vehicle.name + ": link " + vehicle.link + " is down");
    } else if (vehicle.link_state == LinkHealth::silent) {
      add(AlertLevel::warning, "vehicle_silent", vehicle.name,
          vehicle.name + ": nothing heard from the vehicle on " + vehicle.link);
    }
    if (vehicle.origin == OriginState::sending) {
      add(AlertLevel::warning, "origin_not_confirmed", vehicle.name,
          vehicle.name + ": GPS origin not confirmed by the vehicle yet");
    } else if (vehicle.origin == OriginState::conflict) {
      add(AlertLevel::error, "origin_conflict", vehicle.name,
          vehicle.name + ": the vehicle has another GPS origin and cannot change it until reboot");
    } else if (vehicle.origin == OriginState::withheld) {
      add(AlertLevel::warning, "origin_withheld", vehicle.name,
          vehicle.name + ": origin not sent: " +
              vehicle.origin_advice.value_or("PX4 before 1.15 would shift its height by it"));
    } else if (vehicle.origin == OriginState::unconfirmed) {
      add(AlertLevel::warning, "origin_unconfirmed", vehicle.name,
          vehicle.name + ": origin never confirmed, no longer sent: " +
              vehicle.origin_advice.value_or("the vehicle never reported it"));
    }
    if (vehicle.setup.state == "blocked") {
      std::string wrong;
      for (const SetupItemView& item : vehicle.setup.items) {
        if (item.severity != "blocks" || (item.status != "wrong" && item.status != "missing")) {
          continue;
        }
        wrong += (wrong.empty() ? "" : ", ") + item.parameter;
      }
      add(AlertLevel::error, "setup_blocked", vehicle.name,
          vehicle.name + ": the vehicle will not fuse mocap as set up (" + wrong +
              "): see its Set-up list");
    } else if (vehicle.setup.state == "no answer") {
      add(AlertLevel::warning, "setup_no_answer", vehicle.name,
          vehicle.name + ": the vehicle answers no parameter reads: its set-up cannot be checked");
    }
    if (vehicle.agreement.verdict == AgreementVerdict::disagree) {
      add(AlertLevel::error, "agreement_failing", vehicle.name,
          vehicle.name + ": the vehicle's own estimate disagrees with mocap (check axes and body)");
    }
  }

  // Drops rising: compare with the oldest sample still inside the window.
  if (!dropped_history_.empty()) now_s = std::max(now_s, dropped_history_.back().first);
  dropped_history_.emplace_back(now_s, station.dropped);
  while (dropped_history_.size() > 1 &&
         dropped_history_[1].first <= now_s - rules_.drops_window_s) {
    dropped_history_.pop_front();
  }
  const std::uint64_t oldest = dropped_history_.front().second;
  if (station.dropped > oldest) {
    add(AlertLevel::warning, "drops_rising", "station",
        std::to_string(station.dropped - oldest) + " mocap frames dropped in the last " +
            std::to_string(static_cast<int>(rules_.drops_window_s)) + " s");
  }
}

}  // namespace mocaplink::web

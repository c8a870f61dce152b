#include "mocaplink/web/core_views.hpp"

namespace mocaplink::web {

BodyView make_body_view(const core::StationBody& body, const core::BodyEstimate* estimate) {
  BodyView view;
  view.name = body.name;
  view.tracked = body.tracked;
  view.mirrored = body.mirrored;
  if (body.ever_tracked) {
    view.p_m = std::array<double, 3>{body.p_world_m.x(), body.p_world_m.y(), body.p_world_m.z()};
    const Eigen::Quaterniond& q = body.q_world_body;
    view.q_wxyz = std::array<double, 4>{q.w(), q.x(), q.y(), q.z()};
  }
  view.frames_tracked = body.frames_tracked;
  if (estimate != nullptr) {
    view.state = estimate->state;
    view.rejected = estimate->counters.rejected_outliers + estimate->counters.invalid_total();
    view.resets = estimate->counters.resets;
  } else if (body.tracked) {
    view.state = core::TrackingState::tracking;
  } else {
    view.state = body.ever_tracked ? core::TrackingState::lost : core::TrackingState::unseen;
  }
  return view;
}

StationView make_station_view(std::string source, const core::StationSnapshot& snapshot,
                              const EstimateLookup& estimate_of) {
  StationView view;
  view.source = std::move(source);
  view.connected = snapshot.connected;
  view.frame_rate_hz = snapshot.frame_rate_hz;
  view.nominal_rate_hz = snapshot.nominal_rate_hz;
  view.latency_ms = snapshot.latency_ms;
  view.jitter_ms = snapshot.jitter_ms;
  view.frames = snapshot.frames;
  view.dropped = snapshot.dropped;
  view.drops_counted = snapshot.drops_counted;
  view.bodies.reserve(snapshot.bodies.size());
  for (const core::StationBody& body : snapshot.bodies) {
    view.bodies.push_back(make_body_view(body, estimate_of ? estimate_of(body.name) : nullptr));
  }
  return view;
}

}  // namespace mocaplink::web

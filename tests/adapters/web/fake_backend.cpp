#include "fake_backend.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mocaplink/config/load.hpp"
#include "mocaplink/core/profile.hpp"

namespace mocaplink::web::testing {
namespace {

/// The fake lab's configuration: the daemon's refusal rules are the configuration's
/// (config::add_vehicle / update_vehicle), so the fake applies them too.
const char* const kLab = R"(
[mocap]
source = "sim://?bodies=3"
[origin]
latitude_deg = 47.3977
longitude_deg = 8.5456
altitude_m = 488.0
[[vehicle]]
name = "quad1"
body = "Body1"
link = "udp://127.0.0.1:14540"
system_id = 1
profile = "px4"
[[vehicle]]
name = "rover"
body = "Body2"
link = "udp://127.0.0.1:14541"
system_id = 2
profile = "custom"
messages = ["hil_gps", "local_position_ned", "att_pos_mocap"]
rate_hz = 20
)";

VehicleView make_vehicle(const config::Vehicle& vehicle, bool paused) {
  VehicleView v;
  v.name = vehicle.spec.name;
  v.body = vehicle.spec.body;
  v.link = config::to_string(vehicle.link);
  v.system_id = vehicle.spec.system_id;
  v.profile = std::string(core::to_string(vehicle.spec.profile));
  v.rate_hz = vehicle.spec.rate_hz;
  v.paused = paused;
  // What a profile sends and whether it sets the origin come from the core, as in the daemon
  // (the fake has an [origin] configured).
  const core::MessageSet messages = core::messages_for(vehicle.spec.profile, vehicle.spec.messages);
  for (const core::MessageKind kind : core::message_kinds()) {
    if (messages.contains(kind)) v.messages.emplace_back(core::to_string(kind));
  }
  for (const auto name : core::message_kind_names()) v.available_messages.emplace_back(name);
  v.origin = core::sends_origin(vehicle.spec.profile, messages) ? OriginState::sending
                                                                : OriginState::not_needed;
  v.timesync.state =
      vehicle.spec.profile == core::Profile::px4 ? TimesyncState::waiting : TimesyncState::off;
  return v;
}

}  // namespace

std::array<double, 3> fake_body_position(std::size_t index, double t_s) {
  const double w = 2.0 * std::numbers::pi / 12.0;  // one lap in 12 s
  switch (index) {
    case 0:
      return {1.5 * std::cos(w * t_s), 1.5 * std::sin(w * t_s), 1.0};
    case 1:
      return {2.0 * std::sin(w * t_s), 1.0 * std::sin(2.0 * w * t_s), 0.5};
    default:
      return {-1.0, 2.0, 0.0};
  }
}

FakeBackend::FakeBackend() {
  config_ = *config::parse_config(kLab, "fake lab").config;
  for (const auto& vehicle : config_.vehicles) {
    vehicles_.push_back(Vehicle{make_vehicle(vehicle, false), 0.0, 0.0});
  }
  // quad1 talks back: heartbeat, timesync, origin confirmed, agreeing estimate.
  VehicleView& q = vehicles_[0].view;
  q.link_state = LinkHealth::up;
  q.last_heard_s = 0.2;
  q.heartbeat = HeartbeatView{"quadrotor", "px4", false, "POSCTL", 0.2};
  q.timesync = TimesyncView{TimesyncState::synced, 1234.5, 0.8};
  q.origin = OriginState::confirmed;
  q.agreement = AgreementView{AgreementVerdict::agree, 0.4, 0.012, std::nullopt, 1.5};
  q.agreement.checked = {"tilt", "yaw", "position"};  // a PX4 on its own compass and GPS
  // quad1's set-up list (what core::VehicleSetup reports for a PX4 1.14 left at its GPS defaults).
  q.autopilot = AutopilotView{"px4", "1.14.3", "px4"};
  q.setup.state = "blocked";
  q.setup.items = {
      {"EKF2_EV_CTRL", 0.0, "15 (horizontal and vertical position, velocity, yaw)", "blocks",
       "wrong", "EKF2 fuses external vision only for the bits set", 15.0, false, "none", ""},
      {"EKF2_HGT_REF", 1.0, "3 (vision)", "degrades", "wrong",
       "height from the barometer drifts indoors", 3.0, true, "none", ""},
      {"EKF2_GPS_CTRL", 0.0, "0 (no GNSS fusion)", "advice", "ok", "no GNSS indoors", std::nullopt,
       false, "none", ""},
  };
  q.statustext = {{"warning", "Preflight Fail: ekf2 missing data", 3.5}};
  q.estimator = EstimatorView{"ESTIMATOR_STATUS", {"attitude"}, {"no horizontal position"}, 0.3};
  q.delay_ms = DelayView{12.0, 0.0, "EKF2_EV_DELAY", 0.0, "capture to mocaplink (median) 11 ms"};
  // rover's own estimate disagrees (a wrong north axis, say).
  VehicleView& r = vehicles_[1].view;
  r.link_state = LinkHealth::up;
  r.last_heard_s = 0.5;
  r.heartbeat = HeartbeatView{"ground_rover", "ardupilotmega", true, "GUIDED", 0.5};
  r.agreement = AgreementView{AgreementVerdict::disagree, 89.7, 0.35};
}

void FakeBackend::accrue(Vehicle& vehicle) const {
  VehicleView& v = vehicle.view;
  const double pose_count =
      vehicle.sent_before +
      (v.paused || v.messages.empty() ? 0.0 : (t_s_ - vehicle.sent_at_s) * v.rate_hz);
  vehicle.sent_before = pose_count;
  vehicle.sent_at_s = t_s_;
  v.sent.clear();
  v.sent_total = 0;
  for (const std::string& message : v.messages) {
    std::string upper = message;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](char c) { return static_cast<char>(std::toupper(c)); });
    v.sent[upper] = static_cast<std::uint64_t>(pose_count);
    v.sent_total += static_cast<std::uint64_t>(pose_count);
  }
  v.sent["HEARTBEAT"] = static_cast<std::uint64_t>(t_s_);
  v.sent_total += static_cast<std::uint64_t>(t_s_);
  v.send_rate_hz = v.paused || v.messages.empty() ? 0.0 : v.rate_hz * 0.998;
}

void FakeBackend::set_status_frozen(bool frozen) {
  std::optional<StatusView> picture;
  if (frozen) picture = status();
  std::lock_guard lock(mutex_);
  frozen_ = std::move(picture);
}

StatusView FakeBackend::status() {
  std::lock_guard lock(mutex_);
  ++status_calls_;
  if (frozen_) return *frozen_;
  StatusView s;
  s.uptime_s = t_s_;
  s.station.source = "sim://?bodies=3";
  s.station.connected = true;
  s.station.frame_rate_hz = 199.7;
  s.station.nominal_rate_hz = 200.0;
  s.station.latency_ms = 2.4;
  s.station.jitter_ms = 0.3;
  s.station.frames = static_cast<std::uint64_t>(t_s_ * 200.0);
  s.station.dropped = 3;
  s.station.bridge_latency_ms = BridgeLatencyView{0.12, 0.1, 0.45, 0.9};
  s.station.late_frames_skipped = 5;
  s.station.superseded_frames = 7;
  s.station.rejected = 2;
  s.station.rejected_reason = "malformed datagram at byte 80: trailing non-zero bytes after 1 item";
  const char* names[] = {"Body1", "Body2", "Body3"};
  for (std::size_t i = 0; i < 3; ++i) {
    BodyView b;
    b.name = names[i];
    b.p_m = fake_body_position(i, t_s_);
    b.q_wxyz = std::array<double, 4>{1.0, 0.0, 0.0, 0.0};
    const bool lost = i == 2;  // Body3 lies on the floor, occluded
    b.state = lost ? core::TrackingState::lost : core::TrackingState::tracking;
    b.tracked = !lost;
    b.frames_tracked = lost ? 120 : s.station.frames;
    b.rejected = i == 1 ? 2 : 0;
    s.station.bodies.push_back(b);
  }
  for (Vehicle& vehicle : vehicles_) {
    accrue(vehicle);
    s.vehicles.push_back(vehicle.view);
  }
  return s;
}

std::optional<ApiError> FakeBackend::apply(const VehicleChange& change) {
  std::lock_guard lock(mutex_);
  auto find = [this](const std::string& name) {
    return std::find_if(vehicles_.begin(), vehicles_.end(),
                        [&](const Vehicle& v) { return v.view.name == name; });
  };
  auto find_config = [this](const std::string& name) -> const config::Vehicle& {
    return *std::find_if(config_.vehicles.begin(), config_.vehicles.end(),
                         [&](const config::Vehicle& v) { return v.spec.name == name; });
  };
  std::optional<ApiError> refused;
  std::visit(
      [&](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, AddVehicle>) {
          if (find(c.name) != vehicles_.end()) {
            refused = ApiError{409, "a vehicle named \"" + c.name + "\" exists", "name"};
            return;
          }
          auto added = config::add_vehicle(config_, c.keys, "POST /api/vehicles");
          if (!added.ok()) {
            refused = refusal(added.errors.front());
            return;
          }
          config_ = std::move(*added.config);
          vehicles_.push_back(Vehicle{make_vehicle(config_.vehicles.back(), c.paused), t_s_, 0.0});
        } else if constexpr (std::is_same_v<T, RemoveVehicle>) {
          auto it = find(c.name);
          if (it == vehicles_.end()) {
            refused = ApiError{404, "no vehicle named " + c.name, ""};
            return;
          }
          vehicles_.erase(it);
          std::erase_if(config_.vehicles, [&](const auto& v) { return v.spec.name == c.name; });
        } else if constexpr (std::is_same_v<T, SetupVehicle>) {
          auto it = find(c.name);
          if (it == vehicles_.end()) {
            refused = ApiError{404, "no vehicle named " + c.name, ""};
            return;
          }
          // Like core::VehicleSetup: only wrong items with a fix, never on an armed vehicle.
          SetupView& setup = it->view.setup;
          if (it->view.heartbeat && it->view.heartbeat->armed) {
            refused = ApiError{409, "the vehicle is armed", c.reboot ? "reboot" : "apply"};
            return;
          }
          for (const std::string& name : c.apply) {
            const auto item = std::find_if(setup.items.begin(), setup.items.end(), [&](auto& i) {
              return i.parameter == name && i.status == "wrong" && i.fix;
            });
            if (item == setup.items.end()) {
              refused = ApiError{409, name + " is not a wrong parameter of the list", "apply"};
              return;
            }
          }
          for (const std::string& name : c.apply) {
            for (SetupItemView& item : setup.items) {
              if (item.parameter != name) continue;
              item.current = item.fix;
              item.fix.reset();
              item.status = "ok";
              item.apply = "confirmed";
              item.apply_note = "set to " + std::to_string(static_cast<int>(*item.current));
            }
          }
          const bool blocks = std::any_of(setup.items.begin(), setup.items.end(), [](auto& i) {
            return i.severity == "blocks" && i.status != "ok";
          });
          setup.state = blocks ? "blocked" : "ready";
        } else {
          auto it = find(c.name);
          if (it == vehicles_.end()) {
            refused = ApiError{404, "no vehicle named " + c.name, ""};
            return;
          }
          auto updated = config::update_vehicle(config_, c.name, c.keys, "PATCH");
          if (!updated.ok()) {
            refused = refusal(updated.errors.front());
            return;
          }
          config_ = std::move(*updated.config);
          accrue(*it);  // counters up to now at the old rate
          for (const auto& key : c.keys) {
            if (key.key == "rate_hz") it->view.rate_hz = find_config(c.name).spec.rate_hz;
            if (key.key == "messages")
              it->view.messages = std::get<std::vector<std::string>>(key.value);
          }
          if (c.paused) it->view.paused = *c.paused;
        }
      },
      change);
  if (!refused) applied_.push_back(change);
  return refused;
}

void FakeBackend::set_time(double t_s) {
  std::lock_guard lock(mutex_);
  t_s_ = t_s;
}

std::vector<VehicleChange> FakeBackend::applied() const {
  std::lock_guard lock(mutex_);
  return applied_;
}

int FakeBackend::status_calls() const {
  std::lock_guard lock(mutex_);
  return status_calls_;
}

}  // namespace mocaplink::web::testing

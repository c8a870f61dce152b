// Fuzz target for the Bridge's inputs from outside: MAVLink bytes from a vehicle link (through the
// StreamParser and decode_message, as the daemon does) and mocap poses with arbitrary values (NaN,
// infinities, huge numbers, non-unit quaternions). Properties beyond "no crash, no sanitizer
// report": every frame the Bridge emits parses back as one valid MAVLink 2 frame from the vehicle's
// (sysid, compid 197), goes to a live vehicle slot, and no vision message ever carries a
// non-finite position. Vehicles are removed and added again between rounds (the dashboard).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <variant>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace {

using namespace mocaplink;

// The vehicle for a slot: system id slot + 1 (check() relies on it).
core::VehicleSpec spec_for(std::size_t slot) {
  core::VehicleSpec quad;
  quad.name = "quad";
  quad.body = "Body1";
  quad.system_id = 1;
  quad.profile = core::Profile::custom;
  quad.messages = {core::MessageKind::odometry,
                   core::MessageKind::vision_position_estimate,
                   core::MessageKind::vision_speed_estimate,
                   core::MessageKind::att_pos_mocap,
                   core::MessageKind::local_position_ned,
                   core::MessageKind::hil_gps};
  quad.rate_hz = 500.0;
  core::VehicleSpec rover;
  rover.name = "rover";
  rover.body = "Body2";
  rover.system_id = 2;
  rover.profile = core::Profile::ardupilot_gps;
  rover.rate_hz = 500.0;
  core::VehicleSpec spec = slot == 0 ? quad : rover;
  spec.system_id = static_cast<std::uint8_t>(slot + 1);
  return spec;
}

core::Bridge make_bridge() {
  core::BridgeConfig c;
  c.origin = core::GeodeticPosition{40.1156786, -88.2243507, 222.196};
  c.vehicles = {spec_for(0), spec_for(1)};
  return std::get<core::Bridge>(core::Bridge::make(c, core::HostTime{}));
}

std::array<bool, 2> g_live{};

double take_double(std::span<const std::uint8_t>& bytes) {
  double v = 0.0;
  if (bytes.size() >= sizeof v) {
    std::memcpy(&v, bytes.data(), sizeof v);
    bytes = bytes.subspan(sizeof v);
  }
  return v;
}

void check(const core::BridgeOutput& out) {
  for (const auto& m : out.messages) {
    const auto parsed = mavlink::parse_frame(m.frame.bytes());
    if (m.vehicle >= g_live.size() || !g_live[m.vehicle]) std::abort();
    if (!parsed || parsed->sysid != m.vehicle + 1 || parsed->compid != 197) std::abort();
    if (const auto* odo = std::get_if<mavlink::Odometry>(&m.message)) {
      if (!std::isfinite(odo->x) || !std::isfinite(odo->y) || !std::isfinite(odo->z)) std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  core::Bridge bridge = make_bridge();
  g_live = {true, true};
  std::span<const std::uint8_t> bytes(data, size);
  // Up to 8 chunks: each is a mocap frame (2 bodies, 7 doubles each) then a MAVLink datagram
  // whose length is the chunk's first byte.
  mavlink::StreamParser parser;
  std::int64_t t_ms = 0;
  for (int round = 0; round < 8 && !bytes.empty(); ++round) {
    core::MocapFrame frame;
    frame.frame_number = static_cast<std::uint64_t>(round + 1);
    frame.capture_time = core::SourceTime{std::chrono::milliseconds(t_ms)};
    for (const char* name : {"Body1", "Body2"}) {
      core::BodySample s;
      s.name = name;
      s.tracked = !bytes.empty() && (bytes[0] & 1) != 0;
      if (!bytes.empty()) bytes = bytes.subspan(1);
      const double px = take_double(bytes);
      const double py = take_double(bytes);
      const double pz = take_double(bytes);
      s.p_world_m = {px, py, pz};
      const double qw = take_double(bytes);
      s.q_world_body = Eigen::Quaterniond(qw, 0.0, 0.0, std::sqrt(std::max(0.0, 1.0 - qw * qw)));
      frame.bodies.push_back(s);
    }
    const core::HostTime now{std::chrono::milliseconds(t_ms + 5)};
    // A control byte: bit k set toggles vehicle k (removed if there, added again if not).
    const std::uint8_t control = bytes.empty() ? 0 : bytes[0];
    if (!bytes.empty()) bytes = bytes.subspan(1);
    for (std::size_t k = 0; k < g_live.size(); ++k) {
      if ((control & (1U << k)) == 0) continue;
      if (g_live[k]) {
        if (!bridge.remove_vehicle(k)) std::abort();
        g_live[k] = false;
      } else {
        const std::size_t slot = bridge.next_slot();
        const auto added = bridge.add_vehicle(spec_for(slot));
        if (!std::holds_alternative<std::size_t>(added) || std::get<std::size_t>(added) != slot) {
          std::abort();
        }
        g_live[slot] = true;
      }
    }
    check(bridge.on_frame(frame, now));
    check(bridge.on_tick(now));
    if (bytes.empty()) break;
    const std::size_t n = std::min<std::size_t>(bytes[0], bytes.size() - 1);
    const auto datagram = bytes.subspan(1, n);
    bytes = bytes.subspan(1 + n);
    parser.feed_datagram(datagram, 0, [&](const mavlink::FrameView& f) {
      const auto message = mavlink::decode_message(f);
      if (!message) return;
      const core::ReceivedMessage received{f.sysid, f.compid, *message};
      check(bridge.on_vehicle_message(f.sysid % 2, received, now));
    });
    t_ms += 10;
  }
  (void)bridge.snapshot(core::HostTime{std::chrono::milliseconds(t_ms)});
  return 0;
}

#include "mocaplink/core/gcs_router.hpp"

#include <algorithm>

#include "mocaplink/mavlink/routing.hpp"

namespace mocaplink::core {
namespace {

std::string peer_name(std::uint8_t sysid, std::uint8_t compid) {
  return std::to_string(sysid) + "/" + std::to_string(compid);
}

}  // namespace

RouteInfo route_info(const mavlink::FrameView& frame) {
  RouteInfo info{frame.sysid, frame.compid};
  // TIMESYNC's payload starts with tc1 (int64); MAVLink 2 drops trailing zero bytes, so an answer
  // is a frame with any non-zero byte among the first eight on the wire.
  constexpr std::uint32_t kTimesync = 111;
  if (frame.msgid == kTimesync) {
    const auto tc1 = frame.payload.first(std::min<std::size_t>(8, frame.payload.size()));
    info.timesync_answer =
        std::any_of(tc1.begin(), tc1.end(), [](std::uint8_t b) { return b != 0; });
  }
  if (const auto target = mavlink::message_target(frame)) {
    info.has_target = true;
    info.target_system = target->system;
    info.target_component = target->component;
  }
  return info;
}

GcsRouter::State& GcsRouter::at(Endpoint endpoint) {
  if (endpoint >= endpoints_.size()) endpoints_.resize(endpoint + 1);
  return endpoints_[endpoint];
}

const GcsRouter::State* GcsRouter::find(Endpoint endpoint) const {
  return endpoint < endpoints_.size() ? &endpoints_[endpoint] : nullptr;
}

void GcsRouter::attach(Endpoint endpoint, Slot slot, std::uint8_t vehicle_sysid) {
  auto& vehicles = at(endpoint).vehicles;
  const bool known = std::any_of(vehicles.begin(), vehicles.end(),
                                 [&](const Attachment& a) { return a.slot == slot; });
  if (!known) vehicles.push_back({slot, vehicle_sysid});
}

void GcsRouter::detach(Slot slot) {
  for (auto& s : endpoints_) {
    std::erase_if(s.vehicles, [&](const Attachment& a) { return a.slot == slot; });
  }
}

std::vector<GcsRouter::Slot> GcsRouter::slots_of(Endpoint endpoint) const {
  std::vector<Slot> out;
  if (const State* s = find(endpoint)) {
    for (const auto& a : s->vehicles) out.push_back(a.slot);
  }
  return out;
}

bool GcsRouter::unused(Endpoint endpoint) const {
  const State* s = find(endpoint);
  return s == nullptr || s->vehicles.empty();
}

void GcsRouter::from_gcs(Endpoint endpoint, const RouteInfo& frame, HostTime now,
                         std::vector<Slot>& out, std::vector<std::string>& notes,
                         const std::string& endpoint_name) {
  State& s = at(endpoint);
  ++s.counters.frames_from_gcs;
  auto peer = std::find_if(s.peers.begin(), s.peers.end(), [&](const Peer& p) {
    return p.sysid == frame.sysid && p.compid == frame.compid;
  });
  if (peer == s.peers.end() && s.peers.size() < kMaxPeers) {
    s.peers.push_back({frame.sysid, frame.compid, now, false});
    peer = std::prev(s.peers.end());
  }
  if (peer != s.peers.end()) {
    peer->last_heard = now;
    if (!peer->connected) {
      peer->connected = true;
      notes.push_back("ground station " + peer_name(frame.sysid, frame.compid) + " on " +
                      endpoint_name + " connected");
    }
  }
  if (frame.timesync_answer) {
    ++s.counters.timesync_answers;  // never to a vehicle (header comment)
    return;
  }
  const std::size_t before = out.size();
  for (const auto& a : s.vehicles) {
    if (!frame.has_target || frame.target_system == 0 || frame.target_system == a.sysid) {
      out.push_back(a.slot);
    }
  }
  if (out.size() == before && !s.vehicles.empty()) ++s.counters.no_route;
}

bool GcsRouter::heard(const State& s, std::uint8_t sysid, std::uint8_t compid) {
  return std::any_of(s.peers.begin(), s.peers.end(), [&](const Peer& p) {
    return p.sysid == sysid && (compid == 0 || p.compid == compid);
  });
}

void GcsRouter::from_vehicle(Slot slot, const RouteInfo& frame, std::vector<Endpoint>& out) {
  for (Endpoint e = 0; e < endpoints_.size(); ++e) {
    State& s = endpoints_[e];
    const bool serves = std::any_of(s.vehicles.begin(), s.vehicles.end(),
                                    [&](const Attachment& a) { return a.slot == slot; });
    if (!serves) continue;
    if (frame.has_target && frame.target_system != 0 &&
        !heard(s, frame.target_system, frame.target_component)) {
      continue;
    }
    ++s.counters.frames_to_gcs;
    out.push_back(e);
  }
}

void GcsRouter::on_tick(HostTime now, std::vector<std::string>& notes,
                        const std::vector<std::string>& endpoint_names) {
  for (Endpoint e = 0; e < endpoints_.size(); ++e) {
    for (Peer& p : endpoints_[e].peers) {
      if (!p.connected || now - p.last_heard < kPeerTimeout) continue;
      p.connected = false;
      notes.push_back("ground station " + peer_name(p.sysid, p.compid) + " on " +
                      (e < endpoint_names.size() ? endpoint_names[e] : std::string("?")) +
                      " gone (silent " + std::to_string(kPeerTimeout.count()) + " s)");
    }
  }
}

const std::vector<GcsRouter::Peer>& GcsRouter::peers(Endpoint endpoint) const {
  static const std::vector<Peer> kNone;
  const State* s = find(endpoint);
  return s != nullptr ? s->peers : kNone;
}

std::size_t GcsRouter::connected_peers(Endpoint endpoint) const {
  const auto& all = peers(endpoint);
  return static_cast<std::size_t>(
      std::count_if(all.begin(), all.end(), [](const Peer& p) { return p.connected; }));
}

GcsRouter::EndpointCounters GcsRouter::counters(Endpoint endpoint) const {
  const State* s = find(endpoint);
  return s != nullptr ? s->counters : EndpointCounters{};
}

}  // namespace mocaplink::core

// GcsRouter: where a frame forwarded between ground stations and vehicles goes (issue 38;
// docs/daemon.md "Ground stations on the vehicle's link"). A vehicle's `gcs` endpoints share its
// link: every frame passes unchanged, and only the route is decided here, the way mavlink-router
// decides it:
//   * a frame without a target, or with target system 0, goes to every side that may have it
//     (from a ground station: every vehicle its endpoint serves; from a vehicle: every endpoint
//     that serves it);
//   * a targeted frame from a ground station goes to the vehicle(s) of that system id behind its
//     endpoint, and nowhere when none is (counted: no_route);
//   * a targeted frame from a vehicle goes to the endpoints where that system (and component,
//     unless the target component is 0) has been heard. So the answers to mocaplink's own
//     requests — addressed to the vehicle's system id and mocaplink's component — stay with
//     mocaplink, and a ground station's answers reach only it;
//   * one exception to "unchanged, everywhere": a ground station's TIMESYNC answer (tc1 ≠ 0)
//     goes to no vehicle (counted: timesync_answers). PX4 takes any TIMESYNC with tc1 > 0 on its
//     link as the answer to its own request (protocols/autopilots.md §3.10), so a ground station
//     that answers (MAVSDK, mavros do) would move PX4's clock offset onto its own clock and
//     misplace every pose mocaplink stamps, or undo mocaplink's withholding on an unsteady clock
//     (vehicle_clock.hpp). Its requests (tc1 = 0) pass: the vehicle's answers are addressed back.
// A ground-station peer is a (system id, component id) heard on an endpoint. It is "connected"
// while heard within kPeerTimeout; it stays known for routing after that, as in mavlink-router.
// At most kMaxPeers peers are kept per endpoint (memory stays bounded whatever is sent); frames
// from others still pass, but are not routed to by target.
// Pure: time is passed in. Not thread-safe (one owner).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/core/time.hpp"
#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::core {

/// What routing needs of a frame: its sender and, for messages that have one, its target
/// (component 0 when the message has only a target system).
struct RouteInfo {
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
  bool has_target = false;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  bool timesync_answer = false;  ///< TIMESYNC (111) with tc1 ≠ 0 (an answer, not a request)
};

/// A frame's sender and, where its message has one, its target (mavlink::message_target).
[[nodiscard]] RouteInfo route_info(const mavlink::FrameView& frame);

class GcsRouter {
 public:
  using Endpoint = std::size_t;  ///< the caller's index of a ground-station endpoint
  using Slot = std::size_t;      ///< the caller's index of a vehicle

  /// A peer silent this long is no longer "connected" (the log says it went).
  static constexpr std::chrono::seconds kPeerTimeout{5};
  static constexpr std::size_t kMaxPeers = 16;

  struct Peer {
    std::uint8_t sysid = 0;
    std::uint8_t compid = 0;
    HostTime last_heard{};
    bool connected = false;
  };
  struct EndpointCounters {
    std::uint64_t frames_to_gcs = 0;     ///< vehicle frames routed to this endpoint
    std::uint64_t frames_from_gcs = 0;   ///< frames this endpoint's ground stations sent
    std::uint64_t no_route = 0;          ///< targeted at no vehicle behind this endpoint: dropped
    std::uint64_t timesync_answers = 0;  ///< TIMESYNC answers of its ground stations: dropped
  };

  /// Endpoint `endpoint` serves the vehicle in `slot`, whose system id is `vehicle_sysid`.
  /// Attaching the same pair twice changes nothing.
  void attach(Endpoint endpoint, Slot slot, std::uint8_t vehicle_sysid);
  /// The vehicle in `slot` is gone: no endpoint serves it any more.
  void detach(Slot slot);
  /// The slots `endpoint` serves (attach order).
  [[nodiscard]] std::vector<Slot> slots_of(Endpoint endpoint) const;
  /// True when no vehicle is attached to `endpoint` any more (its socket can close).
  [[nodiscard]] bool unused(Endpoint endpoint) const;

  /// A frame from a ground station on `endpoint`, heard at `now`: the vehicle slots it goes to
  /// (appended to `out`). A peer heard for the first time, or again after its timeout, adds a note.
  void from_gcs(Endpoint endpoint, const RouteInfo& frame, HostTime now, std::vector<Slot>& out,
                std::vector<std::string>& notes, const std::string& endpoint_name);
  /// A frame from the vehicle in `slot`: the endpoints it goes to (appended to `out`).
  void from_vehicle(Slot slot, const RouteInfo& frame, std::vector<Endpoint>& out);
  /// Peers silent for kPeerTimeout are marked gone, one note each.
  void on_tick(HostTime now, std::vector<std::string>& notes,
               const std::vector<std::string>& endpoint_names);

  [[nodiscard]] const std::vector<Peer>& peers(Endpoint endpoint) const;
  [[nodiscard]] std::size_t connected_peers(Endpoint endpoint) const;
  [[nodiscard]] EndpointCounters counters(Endpoint endpoint) const;

 private:
  struct Attachment {
    Slot slot;
    std::uint8_t sysid;
  };
  struct State {
    std::vector<Attachment> vehicles;
    std::vector<Peer> peers;
    EndpointCounters counters;
  };
  State& at(Endpoint endpoint);
  [[nodiscard]] const State* find(Endpoint endpoint) const;
  static bool heard(const State& s, std::uint8_t sysid, std::uint8_t compid);

  std::vector<State> endpoints_;  // by Endpoint index
};

}  // namespace mocaplink::core

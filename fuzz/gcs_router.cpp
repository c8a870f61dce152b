// Fuzz target for what a ground station may send through a `gcs` endpoint (issue 38): its bytes go
// through the StreamParser (stream mode, as TCP and serial endpoints read them), each frame's
// target through mavlink::message_target, and the route through core::GcsRouter, as the daemon's
// GroundStations does; the same frames then come back as if a vehicle had sent them. Properties
// beyond "no crash, no sanitizer report": a ground station's frame goes only to vehicles attached
// to its endpoint, and to the one with the targeted system id when it names one; a vehicle's frame
// goes only to endpoints that serve it; the peers kept per endpoint stay bounded.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "mocaplink/core/gcs_router.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace {

using namespace mocaplink;

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Endpoint 0 serves vehicles 1 (slot 0) and 2 (slot 1); endpoint 1 serves vehicle 2 only. The
  // first byte, when present, decides whether slot 0 is detached half-way (a vehicle removed).
  core::GcsRouter router;
  router.attach(0, 0, 1);
  router.attach(0, 1, 2);
  router.attach(1, 1, 2);
  const bool detach = size > 0 && (data[0] & 1U) != 0;
  mavlink::StreamParser parser;
  core::HostTime now{std::chrono::seconds(1)};
  std::size_t frames = 0;
  std::vector<std::size_t> out;
  std::vector<std::string> notes;
  bool detached = false;
  parser.feed(std::span<const std::uint8_t>(data, size), 0, [&](const mavlink::FrameView& frame) {
    const core::RouteInfo info = core::route_info(frame);
    const std::size_t endpoint = frames % 2;
    out.clear();
    router.from_gcs(endpoint, info, now, out, notes, "fuzz");
    for (const std::size_t slot : out) {
      const bool attached = endpoint == 0 ? (slot == 1 || (slot == 0 && !detached)) : slot == 1;
      require(attached);
      if (info.has_target && info.target_system != 0) {
        require(info.target_system == static_cast<std::uint8_t>(slot + 1));
      }
    }
    out.clear();
    const std::size_t slot = frames % 2;  // as if that vehicle had sent the same frame
    router.from_vehicle(slot, info, out);
    for (const std::size_t e : out) {
      // Slot 0 is served by endpoint 0 only (until it is detached), slot 1 by both.
      require(slot == 0 ? (e == 0 && !detached) : e <= 1);
    }
    ++frames;
    now += std::chrono::milliseconds(700);
    router.on_tick(now, notes, {"a", "b"});
    if (detach && frames == 8) {
      router.detach(0);
      detached = true;
    }
  });
  require(router.peers(0).size() <= core::GcsRouter::kMaxPeers);
  require(router.peers(1).size() <= core::GcsRouter::kMaxPeers);
  return 0;
}

#include "run_gcs.hpp"

#include <algorithm>
#include <utility>

#include <spdlog/spdlog.h>
#include <asio/post.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/io/make_link.hpp"

namespace mocaplink::app {
namespace {

/// A closed endpoint is destroyed this long after its close, once every
/// completion its close queued has run (io/link.hpp: a link must outlive its
/// handlers).
constexpr auto kRetireEndpointAfter = std::chrono::seconds(3);

}  // namespace

GroundStations::GroundStations(asio::io_context& loop, ToVehicle to_vehicle)
    : loop_(loop), to_vehicle_(std::move(to_vehicle)) {}

GroundStations::~GroundStations() = default;

void GroundStations::add_vehicle(std::size_t slot, const config::Vehicle& vehicle) {
  for (const config::LinkUrl& url : vehicle.gcs) {
    const std::string name = config::to_string(url);
    auto it = std::find_if(endpoints_.begin(), endpoints_.end(),
                           [&](const Endpoint& e) { return e.link && e.url == name; });
    std::size_t index = 0;
    if (it != endpoints_.end()) {
      index = static_cast<std::size_t>(it - endpoints_.begin());
    } else {
      index = endpoints_.size();
      io::LinkOptions options;
      options.name = "ground station " + name;
      options.peer = "a ground station";
      // A ground station's frames are not verified here: the vehicle verifies
      // what it is sent, and a signed frame passes unchanged (mocaplink signs
      // only its own).
      endpoints_.push_back(Endpoint{name, io::make_link(loop_, url, std::move(options))});
      endpoints_.back().link->start(
          [this, index](const mavlink::FrameView& frame, core::HostTime t) {
            on_gcs_frame(index, frame, t);
          },
          [name](io::TransportState state, const std::string& detail) {
            if (state == io::TransportState::down) {
              spdlog::warn("ground stations {}: {}: {}", name, io::to_string(state), detail);
            } else {
              spdlog::info("ground stations {}: {}: {}", name, io::to_string(state), detail);
            }
          });
    }
    router_.attach(index, slot, vehicle.spec.system_id);
  }
}

void GroundStations::remove_vehicle(std::size_t slot) {
  router_.detach(slot);
  const core::HostTime now = io::host_now();
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    Endpoint& e = endpoints_[i];
    if (!e.link || !router_.unused(i)) continue;
    e.link->close(std::chrono::milliseconds(0));
    retired_.push_back(std::move(e.link));
    retired_at_.push_back(now);
  }
}

void GroundStations::on_gcs_frame(std::size_t endpoint, const mavlink::FrameView& frame,
                                  core::HostTime t) {
  slots_.clear();
  std::vector<std::string> notes;
  router_.from_gcs(endpoint, core::route_info(frame), t, slots_, notes, endpoints_[endpoint].url);
  for (const auto& note : notes) spdlog::info("{}", note);
  for (const std::size_t slot : slots_) to_vehicle_(slot, frame.bytes);
}

void GroundStations::from_vehicle(std::size_t slot, const mavlink::FrameView& frame) {
  if (endpoints_.empty()) return;
  targets_.clear();
  router_.from_vehicle(slot, core::route_info(frame), targets_);
  for (const std::size_t e : targets_) {
    // An endpoint no ground station has reached yet (udpin nobody spoke to, tcpin without a
    // connection) is skipped, not counted as a drop: nobody is missing those frames.
    io::Link* link = endpoints_[e].link.get();
    if (link != nullptr && link->state() == io::TransportState::up) (void)link->send(frame.bytes);
  }
}

std::vector<std::string> GroundStations::names() const {
  std::vector<std::string> out;
  out.reserve(endpoints_.size());
  for (const auto& e : endpoints_) out.push_back(e.url);
  return out;
}

void GroundStations::on_tick(core::HostTime now) {
  if (!endpoints_.empty()) {
    std::vector<std::string> notes;
    router_.on_tick(now, notes, names());
    for (const auto& note : notes) spdlog::info("{}", note);
  }
  for (std::size_t i = 0; i < retired_.size();) {
    if (now - retired_at_[i] < kRetireEndpointAfter) {
      ++i;
      continue;
    }
    // Through the loop: the destruction queues behind every completion the
    // close queued.
    asio::post(loop_, [link = std::shared_ptr<io::Link>(std::move(retired_[i]))] {});
    retired_.erase(retired_.begin() + static_cast<std::ptrdiff_t>(i));
    retired_at_.erase(retired_at_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

std::vector<web::GcsEndpointView> GroundStations::views(std::size_t slot) const {
  std::vector<web::GcsEndpointView> out;
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    const Endpoint& e = endpoints_[i];
    const auto slots = router_.slots_of(i);
    if (!e.link || std::find(slots.begin(), slots.end(), slot) == slots.end()) continue;
    const io::LinkCounters c = e.link->counters();
    const core::GcsRouter::EndpointCounters r = router_.counters(i);
    web::GcsEndpointView v;
    v.url = e.url;
    v.state = io::to_string(e.link->state());
    v.peers = router_.connected_peers(i);
    v.frames_to_gcs = c.frames_sent;
    v.frames_from_gcs = r.frames_from_gcs;
    v.dropped = c.dropped_backlog + c.dropped_down + c.send_errors;
    v.no_route = r.no_route;
    v.timesync_answers = r.timesync_answers;
    v.bad_frames = c.parser.bad_crc + c.parser.unknown_incompat + c.parser.truncated_tail;
    out.push_back(std::move(v));
  }
  return out;
}

void GroundStations::sample(std::size_t slot, const io::Link& link, core::HostTime now) {
  if (slot >= meters_.size()) meters_.resize(slot + 1);
  Meter& m = meters_[slot];
  const io::LinkCounters c = link.counters();
  const std::uint64_t own = c.bytes_sent - std::min(c.bytes_sent, c.forwarded_bytes);
  if (m.at == core::HostTime{} || own < m.own_bytes || c.forwarded_bytes < m.forwarded_bytes) {
    m = Meter{now, own, c.forwarded_bytes};  // the first sample, or another link in this slot
    return;
  }
  const double seconds = core::to_seconds(now - m.at);
  if (seconds < 1.0) return;
  m.own_bytes_per_s = static_cast<double>(own - m.own_bytes) / seconds;
  m.forwarded_bytes_per_s = static_cast<double>(c.forwarded_bytes - m.forwarded_bytes) / seconds;
  m.at = now;
  m.own_bytes = own;
  m.forwarded_bytes = c.forwarded_bytes;
}

web::LinkShareView GroundStations::share(std::size_t slot, const io::Link& link) const {
  const io::LinkCounters c = link.counters();
  web::LinkShareView v;
  v.capacity_bytes_per_s = link.capacity_bytes_per_second();
  if (slot < meters_.size()) {
    v.own_bytes_per_s = meters_[slot].own_bytes_per_s;
    v.forwarded_bytes_per_s = meters_[slot].forwarded_bytes_per_s;
  }
  v.forwarded = c.forwarded_sent;
  v.forwarded_dropped = c.forwarded_dropped;
  v.queued_bytes = link.forwarded_queued_bytes();
  return v;
}

void GroundStations::close(std::chrono::milliseconds linger) {
  for (auto& e : endpoints_) {
    if (e.link) e.link->close(linger);
  }
}

}  // namespace mocaplink::app

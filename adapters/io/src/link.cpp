#include "mocaplink/io/link.hpp"

#include <algorithm>
#include <utility>

#include "mocaplink/io/clock.hpp"

namespace mocaplink::io {
namespace {

std::optional<mavlink::SignatureVerifier> make_verifier(
    const std::optional<mavlink::SigningKey>& key) {
  if (!key) return std::nullopt;
  // A configured key means the vehicle signs too: ArduPilot and PX4 with signing enabled reject
  // our unsigned frames, so we reject theirs (mavlink-wire.md §7.5; RADIO_STATUS excepted).
  return mavlink::SignatureVerifier(*key, mavlink::SignatureVerifier::Options{
                                              .unsigned_policy = mavlink::UnsignedPolicy::reject,
                                              .accept_unsigned_radio_status = true,
                                          });
}

}  // namespace

Link::Link(LinkOptions options)
    : options_(std::move(options)),
      verifier_(make_verifier(options_.verify_key)),
      parser_(verifier_ ? &*verifier_ : nullptr),
      backoff_(options_.retry) {
  options_.max_backlog_bytes = std::max(options_.max_backlog_bytes, mavlink::kMaxFrameSize);
}

LinkCounters Link::counters() const noexcept {
  LinkCounters out = counters_;
  out.parser = parser_.counters();
  return out;
}

std::uint64_t Link::verified_timestamp_10us() const noexcept {
  return verifier_ ? verifier_->local_timestamp_10us() : 0;
}

std::size_t Link::receive_datagram(std::span<const std::uint8_t> bytes) {
  counters_.bytes_received += bytes.size();
  const core::HostTime t = host_now();
  std::size_t from_vehicle = 0;
  parser_.feed_datagram(bytes, signing_now_10us(), [&](const mavlink::FrameView& frame) {
    if (!options_.vehicle_system_id || frame.sysid == *options_.vehicle_system_id) ++from_vehicle;
    if (on_frame_) on_frame_(frame, t);
  });
  return from_vehicle;
}

void Link::receive_stream(std::span<const std::uint8_t> bytes) {
  counters_.bytes_received += bytes.size();
  const core::HostTime t = host_now();
  parser_.feed(bytes, signing_now_10us(), [&](const mavlink::FrameView& frame) {
    if (on_frame_) on_frame_(frame, t);
  });
}

void Link::end_stream() {
  const core::HostTime t = host_now();
  parser_.finish(signing_now_10us(), [&](const mavlink::FrameView& frame) {
    if (on_frame_) on_frame_(frame, t);
  });
}

void Link::set_state(TransportState state, const std::string& detail) {
  if (state == state_) return;
  state_ = state;
  if (on_state_) on_state_(state, detail);
}

void Link::report_state(const std::string& detail) {
  if (on_state_) on_state_(state_, detail);
}

void Link::set_handlers(FrameHandler on_frame, StateHandler on_state) {
  on_frame_ = std::move(on_frame);
  on_state_ = std::move(on_state);
}

bool Link::send_forwarded(std::span<const std::uint8_t> frame) {
  if (!send(frame)) {
    ++counters_.forwarded_dropped;
    return false;
  }
  ++counters_.forwarded_sent;
  counters_.forwarded_bytes += frame.size();
  return true;
}

std::size_t Link::send_batch(std::span<const std::span<const std::uint8_t>> frames) {
  std::size_t sent = 0;
  for (const auto& frame : frames) sent += send(frame) ? 1U : 0U;
  return sent;
}

}  // namespace mocaplink::io

// Server side of one DataStream connection, pure (spec §6, §7, §12 "Server emulator"): the
// greeting, the client's requests (ObjectEnums, RequestFrame, RequestNextFrame, Filter, Ping),
// the stream-mode state, and frame packets with the per-client "unchanged" optimisation for static
// types. The adapter owns the socket and calls in; every returned packet is complete (header +
// items) and ready to write.
//
// Not thread-safe: one ServerSession per connection, used from one thread.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "mocaplink/wire/vicon_result.hpp"
#include "mocaplink/wire/vicon_served_frame.hpp"

namespace mocaplink::wire::vicon {

/// Types our emulator offers (greeting): StreamInfo, SubjectInfo, FrameInfo, LocalSegments,
/// GlobalSegments, Timecode, LatencyInfo, ApplicationInfo, FrameRateInfo, ObjectQuality, Contents.
[[nodiscard]] std::vector<std::uint32_t> server_offered_types();

/// Packets to write, in order (also used for lists of item payloads).
using Packets = std::vector<std::vector<std::byte>>;

class ServerSession {
 public:
  /// The first packet to send on accept: ObjectEnums with server_offered_types() (§6.1).
  [[nodiscard]] std::vector<std::byte> greeting() const;

  /// Handles one client packet body. `latest` is the newest produced frame (nullptr before the
  /// first). Returns what to send now: Ping echoes (own packet each, §6.6) and, for RequestFrame(0)
  /// or a satisfiable RequestNextFrame, a frame packet. Errors: malformed items (the caller should
  /// close the connection); the session state is then partly updated but consistent.
  [[nodiscard]] Result<Packets> on_client_packet(std::span<const std::byte> body,
                                                 const ServedFrame* latest);

  /// A new frame was produced: the frame packet for this client if its mode wants it now
  /// (streaming, or an outstanding pre-fetch request), else nullopt.
  [[nodiscard]] std::optional<std::vector<std::byte>> on_new_frame(const ServedFrame& frame);

  /// Encodes `frame` for this client (requested types, filter, unchanged rule) and records it as
  /// sent. Used by the two calls above; public for tests.
  [[nodiscard]] std::vector<std::byte> encode_frame(const ServedFrame& frame);

  [[nodiscard]] bool streaming() const { return streaming_; }
  [[nodiscard]] std::uint32_t pending_next() const { return pending_next_; }
  [[nodiscard]] const std::set<std::uint32_t>& requested() const { return requested_; }

  /// Cap on outstanding RequestNextFrame counts (a client adding u32s cannot overflow it).
  static constexpr std::uint32_t kMaxPendingNext = 1000;

 private:
  [[nodiscard]] bool passes_filter(ItemType type, std::uint32_t filter_id) const;

  /// Until the client's ObjectEnums arrives, the SDK's default set ∩ ours (§6.1, §12).
  std::set<std::uint32_t> requested_ = {1, 2, 5, 23, 26, 37, 39, 40, 100004};
  std::map<std::uint32_t, std::set<std::uint32_t>> filter_;
  bool streaming_ = false;
  std::uint32_t pending_next_ = 0;
  std::uint64_t last_sent_sequence_ = 0;
  /// Static type → encoded items the client currently holds (what we last sent or left unchanged).
  std::map<std::uint32_t, Packets> held_static_;
};

}  // namespace mocaplink::wire::vicon

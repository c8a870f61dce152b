// Client side of a DataStream session, pure: the greeting, what to request, and the static /
// dynamic item caches of spec §7 ("unchanged" items copied forward), turning each frame packet
// into a DecodedFrame. No sockets, no clocks: the adapter feeds packet bodies in.
//
// Not thread-safe: one ClientStream per connection, used from one thread.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mocaplink/wire/vicon_items.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::vicon {

/// The item types a rigid-body client wants (§12 checklist item 2): Contents, StreamInfo,
/// SubjectInfo, FrameInfo, GlobalSegments, Timecode, LatencyInfo, ApplicationInfo, FrameRateInfo.
[[nodiscard]] std::vector<std::uint32_t> client_wanted_types();

/// ObjectEnums to send after the greeting: wanted ∩ offered, plus Contents always (as the SDK).
/// Ascending, no duplicates.
[[nodiscard]] ObjectEnums client_request(const ObjectEnums& offered);

/// The server's first packet must carry ObjectEnums (§6.1); anything else in it is ignored.
/// Errors: malformed items, or no ObjectEnums in the packet.
[[nodiscard]] Result<ObjectEnums> parse_greeting(std::span<const std::byte> body);

/// One subject of a frame, by its root segment (first segment with parent id 0, §8.11).
struct SubjectSample {
  std::string name;          ///< subject name (the SDK's lookup key)
  std::string root_segment;  ///< root segment name; empty if the subject has no root segment
  bool occluded = true;      ///< root segment missing from this frame's GlobalSegments (§9.3)
  std::array<double, 3> translation_mm{};  ///< world, mm, server axes; valid when !occluded
  std::array<double, 9> rotation{};        ///< row-major, server axes; valid when !occluded
};

/// Everything a rigid-body client takes from one frame packet plus the cached static state.
struct DecodedFrame {
  std::uint32_t frame_id = 0;                      ///< FrameInfo as on the wire (not +1, §9.5)
  std::optional<std::int64_t> frame_period_ticks;  ///< StreamInfo, 135 MHz ticks; >0 when set
  bool y_up = false;                               ///< ApplicationInfo = 1 (§9.4)
  std::vector<SubjectSample> subjects;             ///< SubjectInfo order; first of equal names
  std::optional<LatencyInfo> latency;              ///< LatencyInfo when present
  std::optional<Timecode> timecode;
  std::optional<std::uint32_t> hardware_frame;
  std::vector<std::pair<std::string, double>> frame_rates_hz;  ///< FrameRateInfo
};

/// What one packet produced.
struct PacketOutcome {
  /// Set when the packet carried dynamic items and a valid FrameInfo (§7 step 5).
  std::optional<DecodedFrame> frame;
  /// Why a packet with dynamic items gave no frame (no FrameInfo, reserved frame id); else empty.
  std::string frame_dropped_reason;
  std::vector<std::uint64_t> ping_ids;  ///< Ping items (the server's echoes)
  std::size_t unknown_items = 0;        ///< items of types we do not use, skipped (§3)
  std::size_t keep_alives = 0;          ///< KeepAlive items (§6.7)
};

class ClientStream {
 public:
  /// Applies one server packet body (after the greeting) following §7 steps 1–5. On error (a
  /// malformed item) the cached state is left unchanged; the caller should drop the connection,
  /// as the SDK does.
  [[nodiscard]] Result<PacketOutcome> apply(std::span<const std::byte> body);

  /// Forgets all cached items (new connection).
  void reset();

 private:
  struct StaticSet {
    std::optional<StreamInfo> stream_info;
    std::optional<ApplicationInfo> application_info;
    std::vector<SubjectInfo> subjects;
  };
  struct DynamicSet {
    std::optional<FrameInfo> frame_info;
    std::optional<HardwareFrameInfo> hardware_frame;
    std::optional<Timecode> timecode;
    std::optional<LatencyInfo> latency;
    std::optional<FrameRateInfo> frame_rates;
    std::vector<GlobalSegments> global_segments;
  };

  [[nodiscard]] DecodedFrame decode() const;

  StaticSet static_;
  DynamicSet dynamic_;
};

}  // namespace mocaplink::wire::vicon

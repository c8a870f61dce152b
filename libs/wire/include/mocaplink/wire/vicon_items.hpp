// The DataStream items a rigid-body client and our emulator use, with their wire layouts (spec
// §8). Each structure lists its fields in wire order (MOCAPLINK_VICON_FIELDS); parse_item() and
// encode_item() derive both directions from that list. Units are the wire's: translations in mm,
// rotations as row-major 3×3 matrices, times in seconds, frame periods in 135 MHz ticks.
//
// parse_item() never throws and never reads outside the payload; trailing bytes after the last
// field are ignored (forward compatibility, §3). Pure; thread-safe (no shared state).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mocaplink/wire/vicon_codec.hpp"
#include "mocaplink/wire/vicon_protocol.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::vicon {

/// 100001, both directions (§8.1): the types the server can produce / the client wants.
struct ObjectEnums {
  static constexpr ItemType kType = ItemType::object_enums;
  std::vector<std::uint32_t> types;  ///< a set: ascending, no duplicates when we write it
};
MOCAPLINK_VICON_FIELDS(ObjectEnums, s.types)

/// 100002, client → server (§8.2): 1 = ServerPush from now on; 0 = stop and send the latest once.
struct RequestFrame {
  static constexpr ItemType kType = ItemType::request_frame;
  bool streaming = false;
};
MOCAPLINK_VICON_FIELDS(RequestFrame, s.streaming)

/// 100008, client → server (§8.3): further frames wanted in pre-fetch mode (the SDK sends 1).
struct RequestNextFrame {
  static constexpr ItemType kType = ItemType::request_next_frame;
  std::uint32_t count = 1;
};
MOCAPLINK_VICON_FIELDS(RequestNextFrame, s.count)

/// 42, both directions (§8.5, §6.6): the server echoes the client's id unchanged.
struct Ping {
  static constexpr ItemType kType = ItemType::ping;
  std::uint64_t ping_id = 0;
};
MOCAPLINK_VICON_FIELDS(Ping, s.ping_id)

/// 100007, client → server (§8.6): map item type → set of filter ids (subject ids) to send.
struct Filter {
  static constexpr ItemType kType = ItemType::filter;
  std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> filter;
};
MOCAPLINK_VICON_FIELDS(Filter, s.filter)

/// 100004, server → client (§8.7, §7): per-type item counts (unused by the SDK) and the types to
/// copy forward from the previous packet ("unchanged").
struct Contents {
  static constexpr ItemType kType = ItemType::contents;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> table;
  std::vector<std::uint32_t> unchanged;
};
MOCAPLINK_VICON_FIELDS(Contents, s.table, s.unchanged)

/// 1, static (§8.9): frame period in ticks of the 135 MHz stream clock (100 Hz → 1 350 000).
struct StreamInfo {
  static constexpr ItemType kType = ItemType::stream_info;
  std::int64_t frame_period_ticks = 0;
};
MOCAPLINK_VICON_FIELDS(StreamInfo, s.frame_period_ticks)

/// 37, static (§8.10): 0 = Z-up, 1 = Y-up (other values: treated as Z-up, as the SDK does).
struct ApplicationInfo {
  static constexpr ItemType kType = ItemType::application_info;
  std::uint8_t axis_orientation = 0;
};
MOCAPLINK_VICON_FIELDS(ApplicationInfo, s.axis_orientation)

/// One segment of a subject (§8.11). parent_id 0 = root; segment_id is never 0.
struct SegmentInfo {
  std::uint32_t parent_id = 0;
  std::uint32_t segment_id = 0;
  std::array<float, 6> bounds{};  ///< min x,y,z then max x,y,z (inferred; unused by the SDK)
  std::string name;
};
MOCAPLINK_VICON_FIELDS(SegmentInfo, s.parent_id, s.segment_id, s.bounds, s.name)

struct MarkerInfo {
  std::uint32_t marker_id = 0;
  std::string name;
};
MOCAPLINK_VICON_FIELDS(MarkerInfo, s.marker_id, s.name)

struct MarkerAttachment {
  std::uint32_t marker_id = 0;
  std::uint32_t segment_id = 0;
};
MOCAPLINK_VICON_FIELDS(MarkerAttachment, s.marker_id, s.segment_id)

/// 2, static, one item per subject (§8.11).
struct SubjectInfo {
  static constexpr ItemType kType = ItemType::subject_info;
  std::uint32_t subject_id = 0;
  std::string name;
  std::vector<SegmentInfo> segments;
  std::vector<MarkerInfo> markers;
  std::vector<MarkerAttachment> attachments;
};
MOCAPLINK_VICON_FIELDS(SubjectInfo, s.subject_id, s.name, s.segments, s.markers, s.attachments)

/// 40, static in the SDK's cache, one per subject (§8.14): 0.0 bad … 1.0 excellent.
struct ObjectQuality {
  static constexpr ItemType kType = ItemType::object_quality;
  std::uint32_t subject_id = 0;
  double quality = 0.0;
};
MOCAPLINK_VICON_FIELDS(ObjectQuality, s.subject_id, s.quality)

/// 5, dynamic (§8.15). Never kInvalidFrameId.
struct FrameInfo {
  static constexpr ItemType kType = ItemType::frame_info;
  std::uint32_t frame_id = 0;
};
MOCAPLINK_VICON_FIELDS(FrameInfo, s.frame_id)

/// 36, dynamic (§8.16).
struct HardwareFrameInfo {
  static constexpr ItemType kType = ItemType::hardware_frame_info;
  std::uint32_t hardware_frame = 0;
};
MOCAPLINK_VICON_FIELDS(HardwareFrameInfo, s.hardware_frame)

/// 23, dynamic, 17 bytes (§8.17; wire order differs from the SDK's struct order).
struct Timecode {
  static constexpr ItemType kType = ItemType::timecode;
  std::uint8_t hours = 0;
  std::uint8_t minutes = 0;
  std::uint8_t seconds = 0;
  std::uint8_t frames = 0;
  std::uint16_t subframes = 0;
  std::uint16_t subframes_per_frame = 0;
  /// 0 PAL, 1 NTSC, 2 NTSC drop, 3 Film 24, 4 NTSC film 23.98, 5 ATSC 30, 0xFFFFFFFF none.
  std::uint32_t standard = 0xFFFFFFFF;
  std::uint32_t user_bits = 0;
  std::uint8_t field_flag = 0;
  friend bool operator==(const Timecode&, const Timecode&) = default;
};
MOCAPLINK_VICON_FIELDS(Timecode, s.hours, s.minutes, s.seconds, s.frames, s.subframes,
                       s.subframes_per_frame, s.standard, s.user_bits, s.field_flag)

/// One latency sample (§8.18): duration since the previous sample, seconds.
struct LatencySample {
  std::string name;
  double seconds = 0.0;
};
MOCAPLINK_VICON_FIELDS(LatencySample, s.name, s.seconds)

/// 26, dynamic (§8.18). Total latency = sum of the samples.
struct LatencyInfo {
  static constexpr ItemType kType = ItemType::latency_info;
  std::vector<LatencySample> samples;
};
MOCAPLINK_VICON_FIELDS(LatencyInfo, s.samples)

/// 39, dynamic (§8.19): named rates in Hz (not the stream rate, which comes from StreamInfo).
struct FrameRateInfo {
  static constexpr ItemType kType = ItemType::frame_rate_info;
  std::vector<std::pair<std::string, double>> rates_hz;
};
MOCAPLINK_VICON_FIELDS(FrameRateInfo, s.rates_hz)

/// One segment pose, 100 bytes (§8.20): translation in mm; rotation row-major, R·p_segment + t =
/// p_world, i.e. the columns of R are the segment axes in the world (§9.2).
struct SegmentPose {
  std::uint32_t segment_id = 0;
  std::array<double, 3> translation_mm{};
  std::array<double, 9> rotation{};
};
MOCAPLINK_VICON_FIELDS(SegmentPose, s.segment_id, s.translation_mm, s.rotation)

/// 9 GlobalSegments / 8 LocalSegments, dynamic, one item per subject (§8.20). A segment missing
/// from `segments` (or a subject without an item) is occluded in this frame (§9.3).
template <ItemType K>
struct SegmentPoses {
  static constexpr ItemType kType = K;
  std::uint32_t subject_id = 0;
  std::vector<SegmentPose> segments;
};
template <ItemType K>
auto fields(SegmentPoses<K>& s) {
  return std::tie(s.subject_id, s.segments);
}
template <ItemType K>
auto fields(const SegmentPoses<K>& s) {
  return std::tie(s.subject_id, s.segments);
}
using GlobalSegments = SegmentPoses<ItemType::global_segments>;
using LocalSegments = SegmentPoses<ItemType::local_segments>;

/// 100003 KeepAlive (§6.7): empty payload; ignored by readers.
struct KeepAlive {
  static constexpr ItemType kType = ItemType::keep_alive;
};
[[maybe_unused]] inline auto fields(const KeepAlive&) {
  return std::tuple<>();
}

/// Any item structure above.
template <typename T>
concept Item = requires {
  { T::kType } -> std::convertible_to<ItemType>;
}
&&codec::HasFields<T>;

/// Decodes one item payload (the bytes after the item header). `base_offset` is added to error
/// offsets so they point into the whole packet. Errors: "truncated …", counts beyond the payload.
template <Item T>
[[nodiscard]] Result<T> parse_item(std::span<const std::byte> payload,
                                   std::size_t base_offset = 0) {
  codec::Reader r(payload, base_offset);
  T out{};
  if (!codec::read(r, out)) {
    ParseError e = r.error();
    e.reason = item_type_name(to_u32(T::kType)) + ": " + e.reason;
    return e;
  }
  return out;
}

/// Appends the payload bytes of `item` (no item header) to `out`.
template <Item T>
void encode_item_payload(const T& item, std::vector<std::byte>& out) {
  codec::Writer w(out);
  codec::write(w, item);
}

}  // namespace mocaplink::wire::vicon

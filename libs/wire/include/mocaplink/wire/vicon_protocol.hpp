// Vicon DataStream ("CGStream") protocol constants: packet tag, item type ids, caching classes.
// Facts from /work/shared/protocols/vicon-datastream.md §3, §4 and §7 (derived from the MIT Vicon
// DataStream SDK 1.12.0 and checked against it). Pure constants; thread-safe.
#pragma once

#include <cstdint>
#include <string>

namespace mocaplink::wire::vicon {

/// First u32 of every packet in both directions ("Objects" tag, §3). Bytes on the wire: 01 00 2B
/// 1A.
inline constexpr std::uint32_t kPacketTag = 0x1A2B0001;
/// Packet header: tag u32 + body length u32 (§3).
inline constexpr std::size_t kPacketHeaderBytes = 8;
/// Item header: type u32 + payload length u32 (§3).
inline constexpr std::size_t kItemHeaderBytes = 8;
/// The DataStream server's TCP port (§1).
inline constexpr std::uint16_t kDefaultPort = 801;
/// Ticks per second of the clock StreamInfo's frame period is counted in (§8.9).
inline constexpr double kStreamClockHz = 135'000'000.0;
/// FrameInfo.frame_id value the SDK reserves for "no frame yet"; a server never sends it (§8.15).
inline constexpr std::uint32_t kInvalidFrameId = 0xFFFFFFFF;
/// Filter id of items that have none (§4, §6.8).
inline constexpr std::uint32_t kNoFilterId = 0xFFFFFFFF;

/// Item type ids (§4). Values outside this list occur on the wire and are skipped by readers, so
/// an ItemType may hold any u32.
enum class ItemType : std::uint32_t {
  stream_info = 1,
  subject_info = 2,
  frame_info = 5,
  labeled_recons = 6,
  unlabeled_recons = 7,
  local_segments = 8,
  global_segments = 9,
  timecode = 23,
  labeled_recon_ray_assignments = 25,
  latency_info = 26,
  subject_topology = 28,
  subject_health = 29,
  apex_haptics = 35,
  hardware_frame_info = 36,
  application_info = 37,
  frame_rate_info = 39,
  object_quality = 40,
  ping = 42,
  lightweight_segments = 901,
  subject_scale = 28001,
  object_enums = 100001,
  request_frame = 100002,
  keep_alive = 100003,
  contents = 100004,
  start_multicast_sender = 100005,
  stop_multicast_sender = 100006,
  filter = 100007,
  request_next_frame = 100008,
};

/// How the SDK client caches an item type between packets (§4 column "Class", §7).
enum class ItemClass {
  static_item,   ///< scene description; replaced as a set when any static item arrives
  dynamic_item,  ///< per-frame data; a packet with any dynamic item delivers a frame
  control,       ///< handshake/control items (ObjectEnums, Contents, Ping, requests, …)
  unknown,       ///< not classified here: skipped by the client
};

[[nodiscard]] constexpr std::uint32_t to_u32(ItemType t) {
  return static_cast<std::uint32_t>(t);
}

/// Caching class of a type id (§4). Types the SDK does not copy forward even when listed as
/// unchanged (force plate, voltage, centroid tracks) are never requested by us: they are `unknown`.
[[nodiscard]] ItemClass item_class(std::uint32_t type);

/// Name of a type id as in the spec ("GlobalSegments"), or "type <n>" for unknown ids.
[[nodiscard]] std::string item_type_name(std::uint32_t type);

[[nodiscard]] constexpr const char* to_string(ItemClass c) {
  switch (c) {
    case ItemClass::static_item:
      return "static";
    case ItemClass::dynamic_item:
      return "dynamic";
    case ItemClass::control:
      return "control";
    case ItemClass::unknown:
      return "unknown";
  }
  return "unknown";
}

/// The DataStream stream modes (§6.2–6.4), as chosen by the client.
enum class StreamMode {
  server_push,      ///< RequestFrame(1) once; the server sends every new frame
  client_prefetch,  ///< RequestNextFrame(1) after every frame ("ClientPullPreFetch")
  client_pull,      ///< RequestFrame(0) per frame; the server answers with its latest frame
};

[[nodiscard]] constexpr const char* to_string(StreamMode m) {
  switch (m) {
    case StreamMode::server_push:
      return "push";
    case StreamMode::client_prefetch:
      return "prefetch";
    case StreamMode::client_pull:
      return "pull";
  }
  return "unknown";
}

}  // namespace mocaplink::wire::vicon

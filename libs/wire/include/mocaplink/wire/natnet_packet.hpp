// OptiTrack NatNet packets (/work/shared/protocols/natnet.md): the 4-byte header, server info,
// connect, requests/responses, model definitions and frames of data, for bitstream versions 3.0 to
// 4.x, plus the 2.x frame layout (§6) read-only. Parsers are bounds-checked and never allocate
// more than the bytes present justify (every element of a counted list needs at least one wire
// byte, and elements are appended as they parse); every parse must end exactly at the payload end.
// Encoders write what the parsers read (the emulator's wire format). Pure; thread-safe.
#pragma once

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::natnet {

/// The wire library's value-or-ParseError (shared with the Vicon codecs).
template <typename T>
using Result = vicon::Result<T>;

inline constexpr std::uint16_t kDefaultCommandPort = 1510;
inline constexpr std::uint16_t kDefaultDataPort = 1511;
inline constexpr std::array<std::uint8_t, 4> kDefaultMulticastGroup = {239, 255, 42, 99};
inline constexpr std::size_t kHeaderBytes = 4;
/// Receive buffers hold any UDP datagram (§1: 65 503 bytes of payload at most).
inline constexpr std::size_t kMaxDatagramBytes = 65536;
inline constexpr std::size_t kMaxNameBytes = 256;  ///< MAX_NAMELENGTH, NUL included
/// §8 sanity limits: more than these is corruption.
inline constexpr std::size_t kMaxRigidBodies = 2000;
inline constexpr std::size_t kMaxMarkers = 16000;

enum class MessageId : std::uint16_t {
  connect = 0,
  server_info = 1,
  request = 2,
  response = 3,
  request_model_def = 4,
  model_def = 5,
  request_frame = 6,
  frame_of_data = 7,
  message_string = 8,
  disconnect = 9,
  keep_alive = 10,
  disconnect_by_timeout = 11,
  echo_request = 12,
  echo_response = 13,
  discovery = 14,
  unrecognized_request = 100,
};

/// Frame params bits (§4.7).
inline constexpr std::uint16_t kParamRecording = 0x01;
inline constexpr std::uint16_t kParamModelsChanged = 0x02;
inline constexpr std::uint16_t kParamEditMode = 0x04;  ///< also "bitstream changed" in the samples
inline constexpr std::uint16_t kParamBitstreamChanged = 0x08;

/// A bitstream version (major, minor), compared as a pair.
struct Version {
  std::uint8_t major = 4;
  std::uint8_t minor = 1;
  auto operator<=>(const Version&) const = default;
  [[nodiscard]] bool at_least(std::uint8_t maj, std::uint8_t min) const {
    return *this >= Version{maj, min};
  }
  [[nodiscard]] std::string to_string() const {
    return std::to_string(major) + "." + std::to_string(minor);
  }
};

/// Versions mocaplink decodes: 2.5 ≤ v < 5.0 (2.x frames read-only, §6; 3.0–4.x fully).
[[nodiscard]] bool supported(Version v);

/// One datagram cut into its header and payload.
struct Packet {
  std::uint16_t id = 0;
  std::span<const std::byte> payload;
  std::size_t trailing_bytes = 0;  ///< bytes after the declared payload (ignored, counted)
};

/// The header and payload of one datagram; a datagram shorter than its header says is an error.
[[nodiscard]] Result<Packet> split_packet(std::span<const std::byte> datagram);

/// A whole packet: header (id, payload length) + payload. The payload must be < 65 536 bytes.
[[nodiscard]] std::vector<std::byte> encode_packet(MessageId id,
                                                   std::span<const std::byte> payload);
/// A packet with an empty payload (keep-alive, model-definition request, disconnect, …).
[[nodiscard]] std::vector<std::byte> encode_empty(MessageId id);

// --- connect / server info (§2.1, §2.2)
// -----------------------------------------------------------

struct SenderInfo {
  std::string name;                           ///< ≤ 255 bytes on the wire
  std::array<std::uint8_t, 4> app_version{};  ///< major, minor, build, revision
  std::array<std::uint8_t, 4> natnet_version{};
};

struct ConnectRequest {
  SenderInfo sender;
  /// Requested bitstream (4.x connection options); all zero = the server's default.
  std::array<std::uint8_t, 4> requested_bitstream{};
};

/// NAT_CONNECT payload: 264-byte sender block (+ the 5/9 bytes of connection options).
[[nodiscard]] Result<ConnectRequest> parse_connect(std::span<const std::byte> payload);
/// The 269-byte NAT_CONNECT form (§2.1), header included.
[[nodiscard]] std::vector<std::byte> encode_connect(const ConnectRequest& request);

struct ServerInfo {
  SenderInfo sender;                 ///< natnet_version bytes 0–1 are the bitstream version
  bool has_connection_info = false;  ///< the 3.0+ fields below were present
  std::uint64_t clock_hz = 0;        ///< high-resolution clock, ticks per second
  std::uint16_t data_port = kDefaultDataPort;
  bool multicast = true;
  std::array<std::uint8_t, 4> multicast_group = kDefaultMulticastGroup;

  [[nodiscard]] Version version() const {
    return Version{sender.natnet_version[0], sender.natnet_version[1]};
  }
};

/// NAT_SERVERINFO payload: 264 bytes (before 3.0) or 279 bytes (3.0+).
[[nodiscard]] Result<ServerInfo> parse_server_info(std::span<const std::byte> payload);
/// NAT_SERVERINFO packet; the 279-byte form when has_connection_info.
[[nodiscard]] std::vector<std::byte> encode_server_info(const ServerInfo& info);

// --- requests, responses, echo (§2.3, §2.5)
// -------------------------------------------------------

/// NAT_REQUEST / NAT_MESSAGESTRING payload: one NUL-terminated string filling the payload.
[[nodiscard]] Result<std::string> parse_string_payload(std::span<const std::byte> payload);
/// A packet whose payload is `text` and its NUL (NAT_REQUEST, NAT_MESSAGESTRING).
[[nodiscard]] std::vector<std::byte> encode_string_packet(MessageId id, const std::string& text);
/// A NAT_RESPONSE's text ("Bitstream,4.1.0"), NUL-terminated or not: the text up to the first NUL,
/// or the whole payload when it has none.
[[nodiscard]] std::string parse_response_text(std::span<const std::byte> payload);
/// NAT_RESPONSE with `text` and no NUL, as Motive seems to send it: OptiTrack's own Python client
/// (NatNet SDK 4.1 to 2025) reads the rest of the datagram as the reply and fails on a NUL in it
/// ("int() ... '0\x00'"), which it would against every Motive if Motive sent one.
[[nodiscard]] std::vector<std::byte> encode_response_text(const std::string& text);

struct EchoResponse {
  std::uint64_t client_value = 0;
  std::uint64_t server_rx_ticks = 0;
};
[[nodiscard]] Result<std::uint64_t> parse_echo_request(std::span<const std::byte> payload);
[[nodiscard]] std::vector<std::byte> encode_echo_response(const EchoResponse& echo);

// --- model definitions (§3)
// -----------------------------------------------------------------------

struct RigidBodyDescription {
  std::string name;
  std::int32_t id = 0;
  std::int32_t parent_id = -1;
  std::array<float, 3> offset{};
  std::array<float, 4> quat_offset{0.0f, 0.0f, 0.0f, 1.0f};  ///< qx, qy, qz, qw (4.2+)
  std::vector<std::array<float, 3>> marker_positions;        ///< 3.0+
  std::vector<std::int32_t> marker_labels;                   ///< 3.0+, same count
  std::vector<std::string> marker_names;                     ///< 4.0+, same count
};

struct MarkerSetDescription {
  std::string name;
  std::vector<std::string> marker_names;
};

struct ModelDefinitions {
  std::vector<RigidBodyDescription> rigid_bodies;  ///< type-1 datasets only (§3.4)
  std::vector<MarkerSetDescription> marker_sets;
  std::size_t other_datasets = 0;    ///< skeletons, force plates, devices, cameras, assets
  std::size_t unknown_datasets = 0;  ///< 4.1+: skipped by size
  std::size_t size_mismatches = 0;   ///< 4.1+: size_bytes disagreed with the parse (size trusted)
};

/// NAT_MODELDEF payload in bitstream `v`. Before 4.1 an unknown type is an error.
[[nodiscard]] Result<ModelDefinitions> parse_model_definitions(std::span<const std::byte> payload,
                                                               Version v);
/// NAT_MODELDEF packet with these marker sets and rigid bodies (marker sets first).
[[nodiscard]] std::vector<std::byte> encode_model_definitions(const ModelDefinitions& defs,
                                                              Version v);

// --- frame of data (§4)
// ---------------------------------------------------------------------------

struct RigidBodySample {
  std::int32_t id = 0;
  std::array<float, 3> position{};                           ///< m, server world
  std::array<float, 4> orientation{0.0f, 0.0f, 0.0f, 1.0f};  ///< qx, qy, qz, qw
  float mean_error = 0.0f;
  std::int16_t params = 0;  ///< bit 0 = tracking valid (2.6+; always valid before)
  [[nodiscard]] bool tracking_valid() const { return (params & 0x01) != 0; }
};

struct MarkerSetSample {
  std::string name;
  std::vector<std::array<float, 3>> markers;
};

struct LabeledMarker {
  std::int32_t id = 0;
  std::array<float, 3> position{};
  float size = 0.0f;
  std::int16_t params = 0;
  float residual = 0.0f;  ///< 3.0+
};

struct FrameOfData {
  std::int32_t frame_number = 0;
  std::vector<MarkerSetSample> marker_sets;
  std::vector<std::array<float, 3>> other_markers;
  std::vector<RigidBodySample> rigid_bodies;
  std::size_t skeletons = 0;  ///< parsed and skipped
  std::size_t assets = 0;     ///< 4.1+, parsed and skipped
  std::vector<LabeledMarker> labeled_markers;
  std::size_t force_plates = 0;
  std::size_t devices = 0;
  float software_latency_s = 0.0f;  ///< 2.x only
  std::uint32_t timecode = 0;
  std::uint32_t timecode_subframe = 0;
  double timestamp_s = 0.0;
  std::uint64_t mid_exposure_ticks = 0;   ///< 3.0+
  std::uint64_t data_received_ticks = 0;  ///< 3.0+
  std::uint64_t transmit_ticks = 0;       ///< 3.0+
  std::uint32_t precision_s = 0;          ///< 4.1+
  std::uint32_t precision_fraction = 0;   ///< 4.1+
  std::uint16_t params = 0;               ///< §4.7 bits
};

/// NAT_FRAMEOFDATA payload in bitstream `v` (2.5 ≤ v < 5.0).
[[nodiscard]] Result<FrameOfData> parse_frame(std::span<const std::byte> payload, Version v);
/// NAT_FRAMEOFDATA packet in bitstream `v` ≥ 3.0 (skeletons, assets, force plates and devices are
/// written empty).
[[nodiscard]] std::vector<std::byte> encode_frame(const FrameOfData& frame, Version v);

}  // namespace mocaplink::wire::natnet

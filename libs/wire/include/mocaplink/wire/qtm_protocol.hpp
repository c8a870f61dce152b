// Qualisys QTM real-time protocol, little-endian port (/work/shared/protocols/qtm-rt.md): packet
// framing (§2), command/string/event packets, and data packets with the four 6DOF components
// (§4). Pure: bounds-checked parsers (every count is checked against the bytes present before
// anything is allocated for it) and the matching encoders. Thread-safe (no state).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::qtm {

/// The value-or-ParseError result shared with the other wire parsers.
template <typename T>
using Result = vicon::Result<T>;
using vicon::parse_error;

inline constexpr std::uint16_t kDefaultPort = 22223;  ///< base port + 1: little-endian (§1)
inline constexpr std::size_t kHeaderBytes = 8;        ///< i32 size (incl. header), i32 type
/// Cap on one packet: a 6D component of 1000 bodies is 52 kB; parameter XML a few hundred kB.
inline constexpr std::uint32_t kDefaultMaxPacketBytes = 4u * 1024u * 1024u;
/// `QTM RT Interface connected` + NUL is the welcome (§3.1); clients compare the prefix.
inline constexpr std::string_view kWelcome = "QTM RT Interface connected";
inline constexpr std::string_view kMaxClientsError =
    "Connection refused. Max number of clients reached.";
/// Protocol versions mocaplink's client negotiates, newest first (§3.1: 1.28 … 1.18).
inline constexpr int kNewestMinor = 28;
inline constexpr int kOldestMinor = 18;
/// From this minor version on, the 6D parameters use the §5.2 format (no <Bodies> count).
inline constexpr int kNewXmlFromMinor = 21;

enum class PacketType : std::uint32_t {
  error = 0,
  command = 1,
  xml = 2,
  data = 3,
  no_more_data = 4,
  c3d_file = 5,
  event = 6,
  discover = 7,
  qtm_file = 8,
};

/// §2.3 event numbers (one byte).
enum class Event : std::uint8_t {
  connected = 1,
  connection_closed = 2,
  capture_started = 3,
  capture_stopped = 4,
  calibration_started = 6,
  calibration_stopped = 7,
  rt_from_file_started = 8,
  rt_from_file_stopped = 9,
  waiting_for_trigger = 10,
  camera_settings_changed = 11,
  qtm_shutting_down = 12,
  capture_saved = 13,
};

/// After these events the body list and the stream are suspect: re-read the parameters (§2.3).
[[nodiscard]] bool invalidates_parameters(std::uint8_t event);

/// The four 6DOF component types (§4.1).
enum class Component : std::uint32_t {
  six_d = 5,
  six_d_euler = 6,
  six_d_residual = 11,
  six_d_euler_residual = 12,
};

/// "6D", "6DEuler", "6DRes", "6DEulerRes" (the StreamFrames spelling).
[[nodiscard]] std::string_view to_string(Component c);
/// The StreamFrames spelling, case-insensitive, or nullopt.
[[nodiscard]] std::optional<Component> component_from_string(std::string_view name);
/// Bytes per body of the component (protocol ≥ 1.8): 48, 24, 52, 28 (§4.3).
[[nodiscard]] std::size_t body_bytes(Component c);
[[nodiscard]] bool has_matrix(Component c);
[[nodiscard]] bool has_residual(Component c);

struct PacketHeader {
  std::uint32_t size = 0;  ///< whole packet, header included
  std::uint32_t type = 0;  ///< PacketType value (unknown types are legal: skip them)
};

/// The 8 header bytes. Errors: fewer than 8 bytes, size < 8 or size > max_packet_bytes.
[[nodiscard]] Result<PacketHeader> parse_header(std::span<const std::byte> bytes,
                                                std::uint32_t max_packet_bytes);

/// One whole packet (a UDP datagram): header + payload, size field equal to the bytes given.
struct PacketView {
  std::uint32_t type = 0;
  std::span<const std::byte> payload;  ///< after the 8 header bytes
};
[[nodiscard]] Result<PacketView> parse_packet(std::span<const std::byte> bytes,
                                              std::uint32_t max_packet_bytes);

/// A packet of `type` around `payload`.
[[nodiscard]] std::vector<std::byte> encode_packet(PacketType type,
                                                   std::span<const std::byte> payload);
/// A command/error/XML packet carrying `text` + NUL (`nul` false: no terminator, as qualisys-rt
/// sends its commands).
[[nodiscard]] std::vector<std::byte> encode_text(PacketType type, std::string_view text,
                                                 bool nul = true);
/// An event packet (size 9).
[[nodiscard]] std::vector<std::byte> encode_event(std::uint8_t event);

/// The text of a command/error/XML payload: up to the first NUL or the end (clients may omit the
/// NUL). Never fails; bytes are taken as they are.
[[nodiscard]] std::string text_of(std::span<const std::byte> payload);

/// One body of a 6DOF component, as on the wire (32-bit floats; §4.3). Fields the component does
/// not carry are left at their defaults (NaN rotation / Euler / residual).
struct Body6d {
  std::array<float, 3> position_mm{};
  /// The nine matrix floats in wire order: column by column (elements 0–2 = first column; §4.3,
  /// unverified against a real server). NaN when the component has no matrix.
  std::array<float, 9> rotation{};
  std::array<float, 3> euler_deg{};  ///< Euler variants only
  float residual = 0.0f;             ///< residual variants only, mm
};

struct SixDof {
  Component type = Component::six_d;
  std::uint16_t drop_rate_permille = 0;
  std::uint16_t out_of_sync_permille = 0;
  std::vector<Body6d> bodies;
};

/// A data packet (type 3) with its 6DOF components; other components are counted and skipped.
struct DataPacket {
  std::int64_t timestamp_us = 0;   ///< marker timestamp, µs from the start of the measurement
  std::uint32_t frame_number = 0;  ///< marker frame number
  std::vector<SixDof> six_dof;
  std::uint32_t other_components = 0;
};

/// Parses the payload of a data packet (after the 8 header bytes). Errors: truncated header,
/// component size < 8 or past the end, a 6DOF component whose size is not 16 + count × body
/// bytes, bytes left after the last component.
[[nodiscard]] Result<DataPacket> parse_data(std::span<const std::byte> payload);

/// The whole data packet (header included) for `packet`.
[[nodiscard]] std::vector<std::byte> encode_data(const DataPacket& packet);

}  // namespace mocaplink::wire::qtm

// VRPN tracker protocol, the part a receive-only client and a tracker server emulator need
// (/work/shared/protocols/vrpn.md): the 24-byte cookie (§2), message framing with its 24-byte
// big-endian header and 8-byte payload padding (§3), sender/type descriptions (§4) and the
// `vrpn_Tracker Pos_Quat` report (§5.1). Pure and bounds-checked: no I/O, no allocation driven by
// a length field beyond the caller's cap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::vrpn {

template <typename T>
using Result = vicon::Result<T>;

inline constexpr std::uint16_t kDefaultPort = 3883;
inline constexpr std::size_t kCookieBytes = 24;
inline constexpr std::size_t kHeaderBytes = 24;
/// Sender and type names, NUL included (vrpn_CNAME_LENGTH).
inline constexpr std::size_t kMaxNameBytes = 100;
/// Largest payload accepted (§3: 64 KiB is ample for trackers).
inline constexpr std::uint32_t kMaxPayloadBytes = 65536 - kHeaderBytes;
/// Our cookie's version (the current vrpn/vrpn source); peers must share the major "07.".
inline constexpr std::string_view kMagic = "vrpn: ver. 07.38";
inline constexpr std::string_view kMagicMajor = "vrpn: ver. 07.";

inline constexpr std::int32_t kSenderDescription = -1;
inline constexpr std::int32_t kTypeDescription = -2;
inline constexpr std::int32_t kUdpDescription = -3;
inline constexpr std::int32_t kLogDescription = -4;

inline constexpr std::string_view kPosQuatType = "vrpn_Tracker Pos_Quat";
inline constexpr std::string_view kVelocityType = "vrpn_Tracker Velocity";
/// The client's health check and the server's answer (vrpn_BaseClass.C: a client sends a ping
/// from its device's sender once a second until a pong from that sender comes back).
inline constexpr std::string_view kPingType = "vrpn_Base ping_message";
inline constexpr std::string_view kPongType = "vrpn_Base pong_message";
inline constexpr std::size_t kPosQuatBytes = 64;

/// The 24-byte cookie with remote log mode `log_mode` ('0' = none; §2).
[[nodiscard]] std::array<std::byte, kCookieBytes> make_cookie(char log_mode = '0');

/// A peer's cookie, accepted: same major version, log mode '0'..'3'.
struct Cookie {
  std::string magic;  ///< "vrpn: ver. 07.38"
  char log_mode = '0';
};
/// Checks a received cookie (§2 "Acceptance"); a different minor version is accepted.
[[nodiscard]] Result<Cookie> parse_cookie(std::span<const std::byte> bytes);

/// Server wall-clock time of a message (struct timeval).
struct Timeval {
  std::uint32_t sec = 0;
  std::uint32_t usec = 0;
  friend bool operator==(const Timeval&, const Timeval&) = default;
};

/// A message header (§3). `length` excludes the payload padding.
struct Header {
  std::uint32_t length = kHeaderBytes;
  Timeval time;
  std::int32_t sender = 0;
  std::int32_t type = 0;
  /// Payload bytes as sent (length − 24).
  [[nodiscard]] std::uint32_t payload_bytes() const {
    return length - static_cast<std::uint32_t>(kHeaderBytes);
  }
  /// Payload bytes on the wire, padding included: the next header starts after them.
  [[nodiscard]] std::uint32_t padded_payload_bytes() const { return (payload_bytes() + 7u) & ~7u; }
};

/// Parses a 24-byte header; refuses length < 24, a payload above `max_payload`, and a time whose
/// microseconds are ≥ 1 000 000.
[[nodiscard]] Result<Header> parse_header(std::span<const std::byte> bytes,
                                          std::uint32_t max_payload = kMaxPayloadBytes);

/// The name in a sender or type description payload (§4): u32 L, then L bytes ending in the one
/// NUL; 2 ≤ L ≤ 100, the payload exactly 4 + L bytes, no control character in the name.
[[nodiscard]] Result<std::string> parse_description(std::span<const std::byte> payload);

/// One `vrpn_Tracker Pos_Quat` report (§5.1): position in metres and the sensor's orientation in
/// the tracker's world, w first.
struct PosQuat {
  std::int32_t sensor = 0;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world_sensor = Eigen::Quaterniond::Identity();
};
/// Parses a Pos_Quat payload (≥ 64 bytes; extra bytes ignored); refuses non-finite numbers and a
/// quaternion whose norm is not 1 within core::kQuaternionUnitTolerance (it is normalised).
[[nodiscard]] Result<PosQuat> parse_pos_quat(std::span<const std::byte> payload);

/// One whole message, header and zero padding included. `sequence` goes into the header's
/// padding word, as the VRPN library writes it (§3; readers never look at it).
[[nodiscard]] std::vector<std::byte> encode_message(Timeval time, std::int32_t sender,
                                                    std::int32_t type,
                                                    std::span<const std::byte> payload,
                                                    std::uint32_t sequence = 0);
/// A sender (kSenderDescription) or type (kTypeDescription) description of `id` = `name`.
[[nodiscard]] std::vector<std::byte> encode_description(Timeval time, std::int32_t kind,
                                                        std::int32_t id, std::string_view name,
                                                        std::uint32_t sequence = 0);
/// A Pos_Quat payload (64 bytes; the padding word repeats the sensor, as the library does).
[[nodiscard]] std::vector<std::byte> encode_pos_quat(const PosQuat& report);
/// A Velocity payload (72 bytes; §5.2, vrpn_Tracker::encode_vel_to): i32 sensor twice, vel[3]
/// (m/s, tracker world frame), vel_quat x, y, z, w (the rotation the sensor undergoes in
/// vel_quat_dt, in the world frame: q(t + dt) = vel_quat · q(t), as vrpn_Tracker_Filter applies
/// it), vel_quat_dt (s).
[[nodiscard]] std::vector<std::byte> encode_velocity(std::int32_t sensor,
                                                     const Eigen::Vector3d& v_m_s,
                                                     const Eigen::Quaterniond& vel_quat,
                                                     double vel_quat_dt_s);

}  // namespace mocaplink::wire::vrpn

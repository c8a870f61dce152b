// Vicon Tracker's UDP object stream (/work/shared/protocols/vicon-tracker-udp.md): the datagram
// parser of §5 and an encoder for the emulator. Little-endian; a datagram is a u32 frame number,
// a u8 item count and items (u8 id, u16 data size, data); an object item (id 0, ≥ 72 bytes) is a
// 24-byte NUL-padded name, translation (mm) and three Euler angles (rad), all f64. Pure and
// bounds-checked: items are walked by their size, nothing is allocated beyond the datagram.
//
// Tracker sends the stream in fixed-size blocks (its "Data Block Size": 256, 512 or 1024 bytes):
// the items, then zero bytes to the block size (docs/sources.md "vicon-udp://" says what the
// evidence for this is). The parser takes zero bytes after the last item, of any length, and
// refuses a tail holding anything else: such a tail is an item the count left out, or bytes that
// are not this stream.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::vicon_udp {

template <typename T>
using Result = vicon::Result<T>;

inline constexpr std::uint16_t kDefaultPort = 51001;
inline constexpr std::size_t kHeaderBytes = 5;
inline constexpr std::size_t kItemHeaderBytes = 3;
inline constexpr std::size_t kObjectBytes = 72;
inline constexpr std::size_t kNameBytes = 24;
inline constexpr std::uint8_t kObjectItem = 0;
/// Bytes of one object item with its header (3 + 72).
inline constexpr std::size_t kObjectItemBytes = kItemHeaderBytes + kObjectBytes;
/// Tracker's most common "Data Block Size" (of 256, 512 and 1024), the emulator's default.
inline constexpr std::size_t kDefaultBlockBytes = 1024;
/// The largest UDP payload over IPv4 (65535 − 20 − 8), the largest block the emulator sends.
inline constexpr std::size_t kMaxDatagramBytes = 65507;

/// How many object items fit in a datagram of `block_bytes` (0: unpadded, as many as the u8
/// count allows): 3 for 256, 6 for 512, 13 for 1024; 0 when not even one fits (below 80).
[[nodiscard]] constexpr std::size_t objects_per_block(std::size_t block_bytes) {
  if (block_bytes == 0) return 255;
  if (block_bytes < kHeaderBytes + kObjectItemBytes) return 0;
  const std::size_t n = (block_bytes - kHeaderBytes) / kObjectItemBytes;
  return n < 255 ? n : 255;
}

/// One object item: the translation in the Vicon world (mm) and the three Euler angles (rad).
struct Object {
  std::string name;
  Eigen::Vector3d t_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d rot_rad = Eigen::Vector3d::Zero();  ///< RotX, RotY, RotZ as sent
  /// All six values exactly 0.0: what a Tracker may send for an object it cannot see (§4.1).
  [[nodiscard]] bool all_zero() const;
};

struct Datagram {
  std::uint32_t frame = 0;
  std::vector<Object> objects;
  std::size_t unknown_items = 0;  ///< items of another id, skipped by their size
  std::size_t padding_bytes = 0;  ///< zero bytes after the last item (the block's padding)
};

/// Parses one datagram by §5: every item walked by its size, unknown ids skipped (counted), an
/// object item at least 72 bytes (extra bytes skipped), names without control characters, finite
/// numbers, |translation| ≤ `max_abs_mm` per axis; after the last item only zero bytes (the
/// block's padding, any length, counted in `padding_bytes`). A non-zero byte there is an error
/// at its offset: "trailing non-zero bytes after N items (byte X of Y is 0xZZ)".
[[nodiscard]] Result<Datagram> parse_datagram(std::span<const std::byte> bytes,
                                              double max_abs_mm = 1e6);

/// Encodes a datagram with the given objects (names longer than 24 bytes are cut to 24), then
/// zero bytes up to `block_bytes` as Tracker pads its blocks (0: no padding, the exact size).
/// The objects must fit: at most objects_per_block(block_bytes) of them (checked, aborts).
[[nodiscard]] std::vector<std::byte> encode_datagram(std::uint32_t frame,
                                                     std::span<const Object> objects,
                                                     std::size_t block_bytes = 0);

/// How the three angles make a rotation (§3, unverified against a real Tracker).
enum class EulerOrder {
  xyz,  ///< R = Rx(RotX)·Ry(RotY)·Rz(RotZ) — the DataStream SDK's "Euler XYZ" (default)
  zyx,  ///< R = Rz(RotZ)·Ry(RotY)·Rx(RotX)
};
[[nodiscard]] std::string_view to_string(EulerOrder order);

/// The rotation object → Vicon world of the angles under `order` (w-first Hamilton).
[[nodiscard]] Eigen::Quaterniond to_quaternion(const Eigen::Vector3d& rot_rad, EulerOrder order);
/// The angles that give `q` under `order` (the emulator's inverse of to_quaternion).
[[nodiscard]] Eigen::Vector3d to_euler(const Eigen::Quaterniond& q, EulerOrder order);

/// Signed distance from `older` to `newer` on the u32 frame counter (wrap-around, §4.7).
[[nodiscard]] constexpr std::int64_t frame_difference(std::uint32_t newer, std::uint32_t older) {
  return static_cast<std::int32_t>(newer - older);
}

}  // namespace mocaplink::wire::vicon_udp

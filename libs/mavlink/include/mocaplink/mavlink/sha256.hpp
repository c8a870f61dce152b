// SHA-256 (FIPS 180-4 §6.2), written for MAVLink 2 signing (mavlink-wire.md §7) so that the
// library needs nothing but the standard library on every target (Windows included).
//
// A plain value: no allocation, trivially copyable. SigningKey absorbs its 32-byte secret once and
// copies that state for every frame it signs or verifies.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mocaplink::mavlink {

/// Incremental SHA-256. Construct (the FIPS 180-4 §5.3.3 initial value), update() any number of
/// times with any split of the message, then finish() once for the 32-byte digest. Messages up to
/// 2^61 − 1 bytes (the length counter is 64 bits of bits). Not thread-safe; copies are independent.
class Sha256 {
 public:
  static constexpr std::size_t kDigestSize = 32;
  static constexpr std::size_t kBlockSize = 64;
  using Digest = std::array<std::uint8_t, kDigestSize>;

  Sha256() noexcept;

  /// Absorbs `data` (may be empty).
  void update(std::span<const std::uint8_t> data) noexcept;

  /// Pads (§5.1.1) and returns the digest. Afterwards the state is spent: assign Sha256{} to hash
  /// another message.
  [[nodiscard]] Digest finish() noexcept;

 private:
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, kBlockSize> block_{};
  std::uint64_t length_bytes_ = 0;
};

}  // namespace mocaplink::mavlink

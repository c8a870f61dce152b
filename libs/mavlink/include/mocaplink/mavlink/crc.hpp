// CRC-16/MCRF4XX (X.25 family) as MAVLink uses it: reflected polynomial 0x8408, initial value
// 0xFFFF, no final XOR (mavlink-wire.md §2). Table-driven (slicing-by-8 for spans).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace mocaplink::mavlink {

inline constexpr std::uint16_t kCrcInit = 0xFFFF;

/// Continues a CRC over `bytes`. Start from kCrcInit.
[[nodiscard]] std::uint16_t crc_accumulate(std::span<const std::uint8_t> bytes,
                                           std::uint16_t crc = kCrcInit);

/// Continues a CRC over one byte.
[[nodiscard]] std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc);

}  // namespace mocaplink::mavlink

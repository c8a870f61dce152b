// Hexadecimal digits ↔ bytes (signing keys, MAVLink frames on the command line). Both cases are
// accepted on input; output is lower case.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mocaplink::text {

/// 0–15 for a hex digit ('0'–'9', 'a'–'f', 'A'–'F'), -1 otherwise.
[[nodiscard]] constexpr int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

[[nodiscard]] constexpr bool is_hex_digit(char c) noexcept {
  return hex_value(c) >= 0;
}

/// Every character is a hex digit (true for "").
[[nodiscard]] bool is_hex(std::string_view text) noexcept;

/// Two lower-case digits per byte.
[[nodiscard]] std::string to_hex(std::span<const std::uint8_t> bytes);

/// The bytes of an even number of hex digits; nullopt for an odd count or a non-digit.
[[nodiscard]] std::optional<std::vector<std::uint8_t>> from_hex(std::string_view hex);

}  // namespace mocaplink::text

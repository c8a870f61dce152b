// Test helper: bytes from a hex dump ("01 00 2b 1a ..."; whitespace ignored), as the spec's
// worked examples print them.
#pragma once

#include <cctype>
#include <cstddef>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace mocaplink::wire::vicon::test {

inline std::vector<std::byte> hex(std::string_view text) {
  std::vector<std::byte> out;
  int high = -1;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) != 0) continue;
    const int v = std::isdigit(static_cast<unsigned char>(c)) != 0
                      ? c - '0'
                      : std::tolower(static_cast<unsigned char>(c)) - 'a' + 10;
    if (v < 0 || v > 15) throw std::invalid_argument("bad hex digit");
    if (high < 0) {
      high = v;
    } else {
      out.push_back(static_cast<std::byte>(high * 16 + v));
      high = -1;
    }
  }
  if (high >= 0) throw std::invalid_argument("odd number of hex digits");
  return out;
}

/// The body of a packet (everything after the 8-byte header).
inline std::vector<std::byte> body_of(const std::vector<std::byte>& packet) {
  return {packet.begin() + 8, packet.end()};
}

}  // namespace mocaplink::wire::vicon::test

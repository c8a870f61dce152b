// Helpers shared by the MAVLink tests: golden-vector loading, float32-aware field equality, bytes
// of a text message.
// Golden-vector JSON ↔ typed messages is mocaplink::mavlink_json (the codec `mocaplink mavlink
// encode` uses); the oracle is the vectors' expected_hex, from the reference implementations.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace mocaplink::mavlink::test {

inline nlohmann::json load_golden() {
  std::ifstream in(std::string(MAVLINK_TEST_DATA_DIR) + "/golden-vectors.json");
  if (!in) throw std::runtime_error("golden-vectors.json not found");
  return nlohmann::json::parse(in);
}

/// The bytes of a string (test messages given as text).
inline std::span<const std::uint8_t> bytes_of(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

/// Same bits, or both NaN (float32-aware equality of a decoded field and an expected value).
template <typename T>
bool same_value(T a, T b) {
  if constexpr (std::is_floating_point_v<T>) {
    if (std::isnan(a) && std::isnan(b)) return true;
    return std::bit_cast<std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>(a) ==
           std::bit_cast<std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>(b);
  } else {
    return a == b;
  }
}

}  // namespace mocaplink::mavlink::test

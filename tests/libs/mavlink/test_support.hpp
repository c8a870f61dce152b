// Helpers shared by the MAVLink tests: hex, golden-vector loading, JSON field values ↔ typed
// message fields (float32-aware, "NaN", decimal-string int64).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::mavlink::test {

inline std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

inline std::string to_hex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (const auto b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0xF];
  }
  return out;
}

inline nlohmann::json load_golden() {
  std::ifstream in(std::string(MAVLINK_TEST_DATA_DIR) + "/golden-vectors.json");
  if (!in) throw std::runtime_error("golden-vectors.json not found");
  return nlohmann::json::parse(in);
}

/// Value of a scalar JSON field as the field's C++ type (decimal strings for 64-bit, "NaN").
template <typename T>
T scalar_from_json(const nlohmann::json& j) {
  if constexpr (std::is_floating_point_v<T>) {
    if (j.is_string()) {
      const auto s = j.get<std::string>();
      if (s == "NaN") return std::numeric_limits<T>::quiet_NaN();
      if (s == "Infinity") return std::numeric_limits<T>::infinity();
      if (s == "-Infinity") return -std::numeric_limits<T>::infinity();
      if (s == "-0") return T(-0.0);
      throw std::runtime_error("bad float " + s);
    }
    return static_cast<T>(j.get<double>());
  } else if constexpr (sizeof(T) == 8) {
    const auto s = j.is_string() ? j.get<std::string>() : j.dump();
    if constexpr (std::is_signed_v<T>) return static_cast<T>(std::stoll(s));
    return static_cast<T>(std::stoull(s));
  } else {
    return static_cast<T>(j.get<std::int64_t>());
  }
}

template <typename T>
void assign_from_json(T& field, const nlohmann::json& j) {
  if constexpr (requires { field.size(); }) {
    for (std::size_t i = 0; i < field.size(); ++i) {
      field[i] = scalar_from_json<std::remove_reference_t<decltype(field[0])>>(j.at(i));
    }
  } else {
    field = scalar_from_json<T>(j);
  }
}

/// The typed message named by a golden vector, fields from its "fields" object (missing = 0).
inline Message message_from_vector(const nlohmann::json& v) {
  auto msg = make_message(v.at("msg").get<std::string>());
  if (!msg) throw std::runtime_error("unknown message " + v.at("msg").get<std::string>());
  std::visit(
      [&](auto& m) {
        for_each_field(m, [&](const FieldInfo& info, auto& field) {
          const auto it = v.at("fields").find(std::string(info.name));
          if (it != v.at("fields").end()) assign_from_json(field, *it);
        });
      },
      *msg);
  return *msg;
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

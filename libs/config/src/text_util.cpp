#include "text_util.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>

namespace mocaplink::config::detail {

std::string join(std::span<const std::string_view> words, std::string_view sep) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) out += sep;
    out += words[i];
  }
  return out;
}

std::string format_number(double value) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kMax = 60;
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const char c = text[i];
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      std::array<char, 8> hex{};
      std::snprintf(hex.data(), hex.size(), "\\x%02x", static_cast<unsigned>(c) & 0xffU);
      out += hex.data();
    } else {
      out += c;
    }
  }
  if (text.size() > kMax) out += "...";
  out += '"';
  return out;
}

namespace {

/// The whole text as a T, a leading '+' allowed (from_chars alone refuses it).
template <typename T>
std::optional<T> parse_whole(std::string_view text) {
  T value{};
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') ++first;
  const auto result = std::from_chars(first, last, value);
  if (text.empty() || result.ec != std::errc{} || result.ptr != last) return std::nullopt;
  return value;
}

}  // namespace

std::optional<long long> parse_integer(std::string_view text) {
  return parse_whole<long long>(text);
}

std::optional<double> parse_double(std::string_view text) {
  return parse_whole<double>(text);
}

}  // namespace mocaplink::config::detail

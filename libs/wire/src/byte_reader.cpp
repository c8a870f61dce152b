#include "mocaplink/wire/byte_reader.hpp"

#include <algorithm>

namespace mocaplink::wire {

std::optional<std::string> ByteReader::cstring(std::size_t max_len) {
  const std::size_t limit = std::min(max_len, remaining());
  const auto window = bytes_.subspan(offset_, limit);
  const auto nul = std::find(window.begin(), window.end(), std::byte{0});
  if (nul == window.end()) return std::nullopt;
  const auto length = static_cast<std::size_t>(nul - window.begin());
  std::string out(reinterpret_cast<const char*>(window.data()), length);
  offset_ += length + 1;
  return out;
}

}  // namespace mocaplink::wire

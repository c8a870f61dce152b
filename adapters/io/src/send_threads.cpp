#include "mocaplink/io/send_threads.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string_view>
#include <thread>

namespace mocaplink::io {

std::size_t max_send_threads(std::string* warning) {
  if (const char* text = std::getenv("MOCAPLINK_SEND_THREADS"); text != nullptr && *text != '\0') {
    const std::string_view value(text);
    std::size_t n = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), n);
    if (error == std::errc{} && end == value.data() + value.size() && n >= 1 && n <= 64) return n;
    if (warning != nullptr) {
      *warning = "MOCAPLINK_SEND_THREADS=" + std::string(value) +
                 " ignored: expected a whole number from 1 to 64";
    }
  }
  const unsigned cores = std::thread::hardware_concurrency();  // 0: unknown
  return std::clamp<std::size_t>(cores, 1, kMaxSendThreads);
}

}  // namespace mocaplink::io

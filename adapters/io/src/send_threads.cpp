#include "mocaplink/io/send_threads.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <string_view>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace mocaplink::io {
namespace {

// The cores this process may run on. On Linux its CPU affinity (taskset, systemd's CPUAffinity=,
// a container's cpuset), which std::thread::hardware_concurrency does not see: it counts the
// machine's online cores, and a send thread for a core the process may not use only waits for
// the others. Elsewhere the machine's cores. 0: unknown.
std::size_t usable_cores() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return static_cast<std::size_t>(n);
  }
#endif
  return std::thread::hardware_concurrency();
}

}  // namespace

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
  return std::clamp<std::size_t>(usable_cores(), 1, kMaxSendThreads);
}

}  // namespace mocaplink::io

#include "mocaplink/io/clock.hpp"

#include <chrono>

#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::io {

core::HostTime host_now() noexcept {
  const auto since_epoch = std::chrono::steady_clock::now().time_since_epoch();
  return core::host_time_from_ns(
      std::chrono::duration_cast<std::chrono::nanoseconds>(since_epoch).count());
}

std::int64_t unix_now_us() noexcept {
  const auto since_epoch = std::chrono::system_clock::now().time_since_epoch();
  return std::chrono::duration_cast<std::chrono::microseconds>(since_epoch).count();
}

std::int64_t unix_ns_of(core::HostTime t) noexcept {
  const std::chrono::nanoseconds since_now = t - host_now();
  return unix_now_us() * 1000 + since_now.count();
}

std::uint64_t signing_now_10us() noexcept {
  return mavlink::signing_timestamp_from_unix_us(unix_now_us());
}

}  // namespace mocaplink::io

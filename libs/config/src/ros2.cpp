// ROS_DOMAIN_ID as rcl reads it (rcl/src/rcl/domain_id.c: strtoul with base 0; "" is the default).
#include <cerrno>
#include <cstdlib>
#include <string>

#include "mocaplink/config/config.hpp"
#include "text_util.hpp"

namespace mocaplink::config {

ValueOrError<std::uint32_t> parse_ros_domain_id(std::string_view text) {
  if (text.empty()) return std::uint32_t{0};
  const std::string s(text);
  const auto refuse = [&] {
    return ValueOrError<std::uint32_t>::failure("ROS_DOMAIN_ID must be a whole number from 0 to " +
                                                std::to_string(kMaxRosDomainId) + ", got " +
                                                detail::quoted(text));
  };
  if (s.front() < '0' || s.front() > '9') return refuse();  // strtoul would take "+", "-", " "
  char* end = nullptr;
  errno = 0;
  const unsigned long value = std::strtoul(s.c_str(), &end, 0);
  if (errno != 0 || end != s.c_str() + s.size() || value > kMaxRosDomainId) return refuse();
  return static_cast<std::uint32_t>(value);
}

}  // namespace mocaplink::config

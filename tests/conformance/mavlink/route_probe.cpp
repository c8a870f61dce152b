// Test-only: message_target over lines of standard input, for node_mavlink_routing.cjs.
// Each line "VERSION MSGID PAYLOAD_HEX" (payload may be empty) prints "SYSTEM COMPONENT" or "-"
// (not addressed); a malformed line prints "error" and makes the exit status 1.
#include <cstdint>
#include <iostream>
#include <sstream>
#include <string>

#include "mocaplink/mavlink/routing.hpp"
#include "mocaplink/text/hex.hpp"

int main() {
  int status = 0;
  std::string line;
  while (std::getline(std::cin, line)) {
    std::istringstream fields(line);
    unsigned version = 0;
    std::uint32_t msgid = 0;
    std::string hex;
    const bool numbers = static_cast<bool>(fields >> version >> msgid);
    fields >> hex;  // absent for an empty payload
    const auto payload = mocaplink::text::from_hex(hex);
    if (!numbers || !payload || version < 1 || version > 2) {
      std::cout << "error\n";
      status = 1;
      continue;
    }
    const auto target =
        mocaplink::mavlink::message_target(msgid, *payload, static_cast<std::uint8_t>(version));
    if (target) {
      std::cout << unsigned{target->system} << ' ' << unsigned{target->component} << '\n';
    } else {
      std::cout << "-\n";
    }
  }
  return status;
}

// No DDS library on this platform (the Windows build: Debian has no MinGW Fast DDS).
#include "dds.hpp"

namespace mocaplink::ros2::detail {

bool dds_available() {
  return false;
}

std::string dds_implementation() {
  return "none: this build has no DDS library (Debian packages none for Windows)";
}

std::unique_ptr<Participant> make_participant(const ParticipantSettings& /*settings*/,
                                              std::string& error) {
  error = "ROS 2 is not available in this build: " + dds_implementation();
  return nullptr;
}

}  // namespace mocaplink::ros2::detail

// One participant per domain and interface in the process (dds.hpp, shared_participant).
#include <map>
#include <mutex>
#include <tuple>

#include "dds.hpp"

namespace mocaplink::ros2::detail {

std::shared_ptr<Participant> shared_participant(const ParticipantSettings& settings,
                                                std::string& error) {
  static std::mutex mutex;
  static std::map<std::tuple<std::uint32_t, std::string, std::string>, std::weak_ptr<Participant>>
      live;
  const std::lock_guard lock(mutex);
  const auto key = std::make_tuple(settings.domain_id, settings.network_interface, settings.name);
  if (auto existing = live[key].lock()) return existing;
  std::shared_ptr<Participant> made = make_participant(settings, error);
  if (made) live[key] = made;
  return made;
}

}  // namespace mocaplink::ros2::detail

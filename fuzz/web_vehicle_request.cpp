// Fuzz target for the dashboard's request bodies (adapters/web vehicle_request): POST and PATCH
// JSON from the network. Properties beyond "no crash, no sanitizer report": every refusal is a
// 4xx with a message; every accepted spec/patch satisfies the documented ranges and spellings.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "mocaplink/core/sender.hpp"
#include "mocaplink/web/vehicle_request.hpp"

namespace {

using namespace mocaplink::web;

void check_error(const ApiError& error) {
  if (error.status < 400 || error.status > 499 || error.error.empty()) std::abort();
}

bool known_messages(const std::vector<std::string>& messages) {
  const auto& names = message_names();
  return std::all_of(messages.begin(), messages.end(), [&](const std::string& m) {
    return std::find(names.begin(), names.end(), m) != names.end();
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto spec = parse_vehicle_spec(text);
  if (!spec.ok()) {
    check_error(spec.error());
  } else {
    const VehicleSpec& s = spec.value();
    if (!is_valid_vehicle_name(s.name) || s.body.empty() || s.system_id == 0 ||
        !(s.rate_hz > 0.0 && s.rate_hz <= mocaplink::core::kMaxSenderRateHz) ||
        !known_messages(s.messages) || (s.profile == "custom") == s.messages.empty()) {
      std::abort();
    }
  }
  const auto patch = parse_vehicle_patch(text, "v");
  if (!patch.ok()) {
    check_error(patch.error());
  } else {
    const VehiclePatch& p = patch.value();
    if (!p.rate_hz && !p.messages && !p.paused) std::abort();
    if (p.rate_hz && !(*p.rate_hz > 0.0 && *p.rate_hz <= mocaplink::core::kMaxSenderRateHz))
      std::abort();
    if (p.messages && !known_messages(*p.messages)) std::abort();
  }
  return 0;
}

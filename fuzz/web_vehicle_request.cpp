// Fuzz target for the dashboard's request bodies (adapters/web vehicle_request): POST, PATCH and
// POST .../setup JSON from the network, on through the configuration's checks they meet in the
// daemon (config::add_vehicle / update_vehicle on the demo configuration). Properties beyond "no
// crash, no sanitizer report": every refusal is a 4xx with a message; an accepted body carries only
// [[vehicle]] keys the endpoint takes; a vehicle the configuration accepts satisfies the
// documented ranges; a refusal by the configuration maps to a 422 naming a key of the request.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/core/sender.hpp"
#include "mocaplink/web/vehicle_request.hpp"

namespace {

using namespace mocaplink;

void check_error(const web::ApiError& error) {
  if (error.status < 400 || error.status > 499 || error.error.empty()) std::abort();
}

void check_keys(const std::vector<config::VehicleKey>& keys,
                const std::vector<std::string_view>& allowed) {
  for (const auto& k : keys) {
    if (std::find(allowed.begin(), allowed.end(), k.key) == allowed.end()) std::abort();
  }
}

void check_refusal(const config::ConfigResult& result,
                   const std::vector<config::VehicleKey>& keys) {
  if (result.ok()) return;
  const web::ApiError error = web::refusal(result.errors.front());
  check_error(error);
  if (error.status != 422) std::abort();
  const bool named = error.field.empty() ||
                     std::any_of(keys.begin(), keys.end(),
                                 [&](const config::VehicleKey& k) { return k.key == error.field; });
  // A required key that is missing is named although the request lacks it.
  if (!named && result.errors.front().message != "missing required key") std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const config::Config base = config::demo_config();
  const auto add = web::parse_vehicle_spec(text);
  if (!add.ok()) {
    check_error(add.error());
  } else {
    check_keys(add.value().keys, {"name", "body", "link", "system_id", "profile", "messages",
                                  "rate_hz", "signing_key"});
    const auto added = config::add_vehicle(base, add.value().keys, "POST /api/vehicles");
    check_refusal(added, add.value().keys);
    if (added.ok()) {
      const config::Vehicle& v = added.config->vehicles.back();
      if (v.spec.name != add.value().name || v.spec.body.empty() || v.spec.system_id == 0 ||
          !(v.spec.rate_hz > 0.0 && v.spec.rate_hz <= mocaplink::core::kMaxSenderRateHz) ||
          (v.spec.profile == mocaplink::core::Profile::custom) == v.spec.messages.empty()) {
        std::abort();
      }
    }
  }
  // POST /api/vehicles/NAME/setup: exactly one of apply (1..32 names of 1..16 of A-Z, 0-9, _)
  // or reboot true — the names reach VehicleSetup::apply, which writes only listed items.
  const auto setup = web::parse_vehicle_setup(text, "demo");
  if (!setup.ok()) {
    check_error(setup.error());
  } else {
    const web::SetupVehicle& s = setup.value();
    if (s.name != "demo" || s.reboot == !s.apply.empty() || s.apply.size() > 32) std::abort();
    for (const std::string& name : s.apply) {
      const bool spelled =
          !name.empty() && name.size() <= 16 && std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
          });
      if (!spelled) std::abort();
    }
  }
  const auto update = web::parse_vehicle_patch(text, "demo");
  if (!update.ok()) {
    check_error(update.error());
  } else {
    const web::UpdateVehicle& u = update.value();
    if (u.keys.empty() && !u.paused) std::abort();
    check_keys(u.keys, {"rate_hz", "messages"});
    const auto updated = config::update_vehicle(base, "demo", u.keys, "PATCH /api/vehicles/demo");
    check_refusal(updated, u.keys);
    if (updated.ok()) {
      const double rate = updated.config->vehicles.front().spec.rate_hz;
      if (!(rate > 0.0 && rate <= mocaplink::core::kMaxSenderRateHz)) std::abort();
    }
  }
  return 0;
}

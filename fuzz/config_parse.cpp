// Fuzz target: configuration text → parse_config, and every line of the input as a --vehicle SPEC,
// --source URL (through the source registry: every built-in source's option parser), --http ADDR
// and link URL, and as a `key=value` of a vehicle added or changed at run time (add_vehicle,
// update_vehicle; values typed as JSON would give them) (libs/config, adapters/sources). Beyond
// "no crash", it checks the library's contract: a Config exists exactly when there are no errors,
// every error has a message and a sane position, and every accepted Config satisfies the
// documented ranges and rules.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/sources/registry.hpp"

namespace {

using mocaplink::config::Config;
using mocaplink::config::ConfigResult;

void require(bool condition) {
  if (!condition) std::abort();
}

void check_config(const Config& c) {
  require(mocaplink::core::are_perpendicular(c.mocap.body_forward, c.mocap.body_up));
  if (const auto* north = std::get_if<mocaplink::core::SignedAxis>(&c.mocap.north)) {
    require(mocaplink::core::are_perpendicular(c.mocap.up, *north));
  }
  for (std::size_t i = 0; i < c.vehicles.size(); ++i) {
    const auto& v = c.vehicles[i];
    require(!v.spec.name.empty() && v.spec.name.size() <= 64 && !v.spec.body.empty());
    require(v.spec.system_id >= 1 && v.spec.component_id >= 2);
    require(v.spec.rate_hz > 0.0 && v.spec.rate_hz <= mocaplink::core::kMaxSenderRateHz);
    require(mocaplink::core::are_perpendicular(v.spec.body_axes.forward(), v.spec.body_axes.up()));
    require((v.spec.profile == mocaplink::core::Profile::custom) == !v.spec.messages.empty());
    for (std::size_t j = 0; j < i; ++j) {
      require(c.vehicles[j].spec.name != v.spec.name);
      require(!(c.vehicles[j].link == v.link && c.vehicles[j].spec.system_id == v.spec.system_id));
    }
  }
  if (!mocaplink::config::is_loopback(c.http.listen.host)) require(c.http.token.size() >= 16);
}

/// "key=value" as a typed VehicleKey: an integer, a number, true/false, a '+'-joined list, or text.
mocaplink::config::VehicleKey typed_key(const std::string& line) {
  const auto eq = line.find('=');
  mocaplink::config::VehicleKey key{line.substr(0, eq), std::string()};
  const std::string value = eq == std::string::npos ? std::string() : line.substr(eq + 1);
  char* end = nullptr;
  const long long integer = std::strtoll(value.c_str(), &end, 10);
  if (!value.empty() && *end == '\0') {
    key.value = static_cast<std::int64_t>(integer);
    return key;
  }
  const double number = std::strtod(value.c_str(), &end);
  if (!value.empty() && *end == '\0') {
    key.value = number;
  } else if (value == "true" || value == "false") {
    key.value = value == "true";
  } else if (value.find('+') != std::string::npos) {
    std::vector<std::string> items;
    for (std::size_t at = 0; at <= value.size();) {
      const auto plus = std::min(value.find('+', at), value.size());
      items.push_back(value.substr(at, plus - at));
      at = plus + 1;
    }
    key.value = items;
  } else {
    key.value = value;
  }
  return key;
}

void check_result(const ConfigResult& result) {
  require(result.ok() == result.errors.empty());
  for (const auto& e : result.errors)
    require(!e.message.empty() && (e.line == 0) == (e.column == 0));
  if (result.config) check_config(*result.config);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto sources = mocaplink::sources::builtin_sources();
  static const auto validate_source = sources.validator();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto checked = [](const ConfigResult& result) {
    check_result(result);
    // An accepted configuration's source is one the registry accepts (what `run` opens).
    if (result.config) require(sources.check(result.config->mocap.source.text).error.empty());
  };
  checked(mocaplink::config::parse_config(text, "fuzz.toml", validate_source));

  // The same bytes as command-line options, one per line (at most 8 lines).
  mocaplink::config::CommandLineOverrides overrides;
  std::vector<mocaplink::config::VehicleKey> keys;
  std::size_t start = 0;
  while (start < text.size() && overrides.vehicles.size() < 8) {
    const auto end = std::min(text.find('\n', start), text.size());
    const std::string line(text.substr(start, end - start));
    const auto shape = mocaplink::config::parse_source_url(line);
    const auto source = sources.check(line);
    require(shape || !source.error.empty());  // the registry never accepts a malformed URL
    // A link that parses round-trips through its canonical form (what `check` prints, the
    // dashboard shows and a shared link is recognised by).
    if (const auto link = mocaplink::config::parse_link_url(line)) {
      const auto again =
          mocaplink::config::parse_link_url(mocaplink::config::to_string(link.value()));
      require(again && again.value() == link.value());
    }
    (void)mocaplink::config::parse_north(line);
    overrides.vehicles.push_back(line);
    keys.push_back(typed_key(line));
    start = end + 1;
  }
  const auto added = mocaplink::config::add_vehicle(mocaplink::config::demo_config(), keys, "fuzz");
  check_result(added);
  if (added.config) require(added.config->vehicles.size() == 2);
  const auto updated =
      mocaplink::config::update_vehicle(mocaplink::config::demo_config(), "demo", keys, "fuzz");
  check_result(updated);
  if (updated.config) require(updated.config->vehicles.size() == 1);
  if (!overrides.vehicles.empty()) {
    overrides.source = overrides.vehicles.front();
    overrides.http = overrides.vehicles.back();
  }
  checked(mocaplink::config::apply_overrides(mocaplink::config::demo_config(), overrides,
                                             "built-in demo", validate_source));
  checked(mocaplink::config::load_config(text, "fuzz.toml", overrides, validate_source));
  return 0;
}

#include "mocaplink/sources/vrpn_options.hpp"

#include <cmath>

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::sources {

namespace {

/// A whole number of milliseconds in [low, high].
std::string read_ms(std::string_view key, std::string_view text, std::uint64_t low,
                    std::uint64_t high, std::chrono::milliseconds& out) {
  std::uint64_t ms = 0;
  std::string error = config::read_count_option(key, text, low, high, ms);
  if (error.empty()) out = std::chrono::milliseconds(static_cast<std::int64_t>(ms));
  return error;
}

}  // namespace

config::ValueOrError<VrpnOptions> parse_vrpn_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<VrpnOptions>;
  std::string_view body = url.body;
  if (body.ends_with('/')) body.remove_suffix(1);
  VrpnOptions options;
  const auto at = body.rfind('@');
  if (at != std::string_view::npos) {
    std::string_view names = body.substr(0, at);
    body.remove_prefix(at + 1);
    if (names != "*") {
      while (true) {
        const auto comma = names.find(',');
        const std::string_view name = names.substr(0, comma);
        if (name.empty() || name.size() >= wire::vrpn::kMaxNameBytes) {
          return Result::failure("vrpn:// tracker names must be 1 to 99 characters, got " +
                                 config::quote(name));
        }
        options.trackers.emplace_back(name);
        if (comma == std::string_view::npos) break;
        names.remove_prefix(comma + 1);
      }
    }
  }
  if (body.find('/') != std::string_view::npos) {
    return Result::failure("vrpn:// takes no path, got " + config::quote(body));
  }
  const auto address = config::parse_host_port(
      body, config::HostPortRules{.port_optional = true, .default_port = wire::vrpn::kDefaultPort});
  if (!address) return Result::failure(address.error());
  options.host = address.value().host;
  options.port = address.value().port;
  for (const auto& [key, value] : url.query) {
    std::string error;
    if (key == "lost_ms") error = read_ms(key, value, 10, 60'000, options.lost);
    if (key == "frozen_ms") error = read_ms(key, value, 0, 60'000, options.frozen);
    if (key == "timeout_ms") error = read_ms(key, value, 100, 600'000, options.timeout);
    if (!error.empty()) return Result::failure(error);
  }
  return options;
}

}  // namespace mocaplink::sources

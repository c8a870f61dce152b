#include "mocaplink/sources/qtm_options.hpp"

#include <charconv>

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::sources {

namespace {

// "1.N" with N in [low, high] → N.
std::optional<int> read_minor(std::string_view text, int low, int high) {
  if (!text.starts_with("1.")) return std::nullopt;
  text.remove_prefix(2);
  int minor = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), minor);
  if (ec != std::errc{} || end != text.data() + text.size() || minor < low || minor > high) {
    return std::nullopt;
  }
  return minor;
}

std::string version_range(int low, int high) {
  return "1." + std::to_string(low) + " to 1." + std::to_string(high);
}

}  // namespace

config::ValueOrError<QtmOptions> parse_qtm_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<QtmOptions>;
  namespace wq = wire::qtm;
  std::string_view body = url.body;
  if (body.ends_with('/')) body.remove_suffix(1);
  if (body.find('/') != std::string_view::npos) {
    return Result::failure("qtm:// takes no path, got " + config::quote(body));
  }
  const auto address = config::parse_host_port(
      body, config::HostPortRules{.port_optional = true, .default_port = wq::kDefaultPort});
  if (!address) return Result::failure(address.error());
  QtmOptions options;
  options.host = address.value().host;
  options.port = address.value().port;
  for (const auto& [key, value] : url.query) {
    if (key == "udp") {
      std::uint64_t port = 0;
      if (auto err = config::read_count_option(key, value, 0, 65535, port); !err.empty()) {
        return Result::failure(err);
      }
      if (port != 0 && port < 1023) {
        return Result::failure("udp must be 0 (any free port) or 1023 to 65535, got " +
                               config::quote(value));
      }
      options.udp_port = static_cast<std::uint16_t>(port);
    } else if (key == "component") {
      const auto c = wq::component_from_string(value);
      if (!c) {
        return Result::failure("component must be 6d, 6dres, 6deuler or 6deulerres, got " +
                               config::quote(value));
      }
      options.component = *c;
    } else if (key == "version") {
      const auto minor = read_minor(value, wq::kOldestMinor, wq::kNewestMinor);
      if (!minor) {
        return Result::failure("version must be " +
                               version_range(wq::kOldestMinor, wq::kNewestMinor) + ", got " +
                               config::quote(value));
      }
      options.newest_minor = *minor;
    }
  }
  return options;
}

config::ValueOrError<QtmEmulatorSettings> parse_qtm_emulator_settings(
    const std::vector<std::pair<std::string, std::string>>& settings) {
  using Result = config::ValueOrError<QtmEmulatorSettings>;
  namespace wq = wire::qtm;
  QtmEmulatorSettings out;
  for (const auto& [key, value] : settings) {
    if (key == "version") {
      const auto minor = read_minor(value, 8, 99);
      if (!minor) {
        return Result::failure("version must be " + version_range(8, 99) +
                               " (the newest protocol served), got " + config::quote(value));
      }
      out.session.max_minor = *minor;
    } else if (key == "components") {
      out.session.components.clear();
      std::string_view rest = value;
      while (!rest.empty()) {
        const auto comma = rest.find(',');
        const std::string_view name = rest.substr(0, comma);
        const auto c = wq::component_from_string(name);
        if (!c) {
          return Result::failure(
              "components must be a comma-separated list of 6d, 6dres, 6deuler, 6deulerres, got " +
              config::quote(value));
        }
        out.session.components.push_back(*c);
        rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
      }
      if (out.session.components.empty()) {
        return Result::failure("components must name at least one component");
      }
    } else if (key == "max_clients") {
      std::uint64_t n = 0;
      if (auto err = config::read_count_option(key, value, 1, 1000, n); !err.empty()) {
        return Result::failure(err);
      }
      out.max_clients = static_cast<std::size_t>(n);
    }
  }
  return out;
}

}  // namespace mocaplink::sources

#include "mocaplink/sources/vicon_options.hpp"

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::sources {

config::ValueOrError<ViconOptions> parse_vicon_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<ViconOptions>;
  std::string_view body = url.body;
  if (body.ends_with('/')) body.remove_suffix(1);  // vicon://host/ as a browser would write it
  if (body.find('/') != std::string_view::npos) {
    return Result::failure("vicon:// takes no path, got " + config::quote(body));
  }
  const auto address = config::parse_host_port(
      body,
      config::HostPortRules{.port_optional = true, .default_port = wire::vicon::kDefaultPort});
  if (!address) return Result::failure(address.error());
  ViconOptions options{address.value().host, address.value().port};
  for (const auto& [key, value] : url.query) {
    if (key != "mode") continue;
    bool found = false;
    for (const auto mode :
         {wire::vicon::StreamMode::server_push, wire::vicon::StreamMode::client_prefetch,
          wire::vicon::StreamMode::client_pull}) {
      if (value == wire::vicon::to_string(mode)) {
        options.mode = mode;
        found = true;
      }
    }
    if (!found) {
      return Result::failure("mode must be push, prefetch or pull, got " + config::quote(value));
    }
  }
  return options;
}

}  // namespace mocaplink::sources

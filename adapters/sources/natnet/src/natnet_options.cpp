#include "mocaplink/sources/natnet_options.hpp"

#include <asio/ip/address_v4.hpp>

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::sources {

namespace {

std::optional<asio::ip::address_v4> ipv4(std::string_view text) {
  asio::error_code ec;
  const auto a = asio::ip::make_address_v4(std::string(text), ec);
  if (ec) return std::nullopt;
  return a;
}

}  // namespace

config::ValueOrError<NatnetOptions> parse_natnet_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<NatnetOptions>;
  std::string_view body = url.body;
  if (body.ends_with('/')) body.remove_suffix(1);
  if (body.find('/') != std::string_view::npos) {
    return Result::failure("natnet:// takes no path, got " + config::quote(body));
  }
  const auto address = config::parse_host_port(
      body, config::HostPortRules{.port_optional = true,
                                  .default_port = wire::natnet::kDefaultCommandPort});
  if (!address) return Result::failure(address.error());
  NatnetOptions options;
  options.host = address.value().host;
  options.command_port = address.value().port;
  for (const auto& [key, value] : url.query) {
    if (key == "local") {
      if (!ipv4(value)) {
        return Result::failure("local must be the IPv4 address of a local interface, got " +
                               config::quote(value));
      }
      options.local = std::string(value);
    } else if (key == "multicast") {
      const auto group = ipv4(value);
      if (!group || !group->is_multicast()) {
        return Result::failure(
            "multicast must be an IPv4 multicast group (224.0.0.0 to 239.255.255.255), got " +
            config::quote(value));
      }
      options.multicast_group = std::string(value);
    } else if (key == "data_port") {
      std::uint64_t port = 0;
      if (auto err = config::read_count_option(key, value, 1, 65535, port); !err.empty()) {
        return Result::failure(err);
      }
      options.data_port = static_cast<std::uint16_t>(port);
    } else if (key == "transport") {
      if (value == "auto") {
        options.transport = NatnetTransport::automatic;
      } else if (value == "multicast") {
        options.transport = NatnetTransport::multicast;
      } else if (value == "unicast") {
        options.transport = NatnetTransport::unicast;
      } else {
        return Result::failure("transport must be auto, multicast or unicast, got " +
                               config::quote(value));
      }
    }
  }
  return options;
}

}  // namespace mocaplink::sources

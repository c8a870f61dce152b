#include "mocaplink/sources/vicon_udp_options.hpp"

#include <asio/ip/address.hpp>

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::sources {

namespace {

/// An IPv4 or IPv6 literal (a socket binds to or compares with addresses, not names).
bool is_ip_literal(const std::string& text) {
  asio::error_code ec;
  (void)asio::ip::make_address(text, ec);
  return !ec;
}

std::string read_option(std::string_view key, std::string_view value, ViconUdpOptions& o) {
  using wire::vicon_udp::EulerOrder;
  std::uint64_t count = 0;
  std::string error;
  if (key == "rotation") {
    if (value == "xyz") {
      o.rotation = EulerOrder::xyz;
    } else if (value == "zyx") {
      o.rotation = EulerOrder::zyx;
    } else {
      error = "rotation must be xyz or zyx, got " + config::quote(value);
    }
  } else if (key == "from") {
    if (!is_ip_literal(std::string(value))) {
      error = "from must be the Tracker's IP address, got " + config::quote(value);
    }
    o.from = value;
  } else if (key == "lost_ms") {
    error = config::read_count_option(key, value, 10, 60'000, count);
    o.lost = std::chrono::milliseconds(static_cast<std::int64_t>(count));
  } else if (key == "frozen") {
    error = config::read_count_option(key, value, 0, 1'000'000, count);
    o.frozen = static_cast<std::uint32_t>(count);
  } else if (key == "arena_m") {
    error = config::read_number_option(key, value, 0.0, 1e6, false, o.arena_m);
  }
  return error;
}

}  // namespace

config::ValueOrError<ViconUdpOptions> parse_vicon_udp_options(const config::UrlParts& url) {
  using Result = config::ValueOrError<ViconUdpOptions>;
  std::string_view body = url.body;
  if (body.ends_with('/')) body.remove_suffix(1);
  if (body.find('/') != std::string_view::npos) {
    return Result::failure("vicon-udp:// takes no path, got " + config::quote(body));
  }
  ViconUdpOptions options;
  if (!body.empty()) {
    const auto address = config::parse_host_port(
        body, config::HostPortRules{.host_optional = true,
                                    .port_optional = true,
                                    .default_port = wire::vicon_udp::kDefaultPort});
    if (!address) return Result::failure(address.error());
    options.port = address.value().port;
    if (!address.value().host.empty()) options.bind_host = address.value().host;
    if (!is_ip_literal(options.bind_host)) {
      return Result::failure("vicon-udp:// binds to a local IP address, got " +
                             config::quote(options.bind_host));
    }
  }
  for (const auto& [key, value] : url.query) {
    std::string error = read_option(key, value, options);
    if (!error.empty()) return Result::failure(error);
  }
  return options;
}

}  // namespace mocaplink::sources

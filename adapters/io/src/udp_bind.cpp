#include "mocaplink/io/udp_bind.hpp"

#include <charconv>
#include <system_error>

namespace mocaplink::io {

std::optional<UdpUrl> parse_udp_url(std::string_view url, std::string& error) {
  constexpr std::string_view kScheme = "udp://";
  if (url.substr(0, kScheme.size()) != kScheme) {
    error = "expected udp://host:port, got '" + std::string(url) + "'";
    return std::nullopt;
  }
  std::string_view rest = url.substr(kScheme.size());
  UdpUrl out;
  std::string_view port_text;
  if (!rest.empty() && rest.front() == '[') {  // [IPv6]:port
    const auto close = rest.find(']');
    if (close == std::string_view::npos || close + 1 >= rest.size() || rest[close + 1] != ':') {
      error = "bad IPv6 address in '" + std::string(url) + "' (use udp://[addr]:port)";
      return std::nullopt;
    }
    out.host = std::string(rest.substr(1, close - 1));
    port_text = rest.substr(close + 2);
  } else {
    const auto colon = rest.rfind(':');
    if (colon == std::string_view::npos) {
      error = "missing port in '" + std::string(url) + "' (udp://host:port)";
      return std::nullopt;
    }
    out.host = std::string(rest.substr(0, colon));
    port_text = rest.substr(colon + 1);
  }
  unsigned port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc{} || end != port_text.data() + port_text.size() || port > 65535 ||
      port_text.empty()) {
    error = "bad port '" + std::string(port_text) + "' in '" + std::string(url) + "' (0-65535)";
    return std::nullopt;
  }
  out.port = static_cast<std::uint16_t>(port);
  return out;
}

std::optional<asio::ip::udp::socket> bind_udp(asio::io_context& loop, const UdpUrl& url,
                                              std::string& error) {
  std::error_code ec;
  asio::ip::udp::resolver resolver(loop);
  const std::string host = url.host.empty() ? "0.0.0.0" : url.host;
  const auto results =
      resolver.resolve(host, std::to_string(url.port), asio::ip::resolver_base::passive, ec);
  if (ec || results.empty()) {
    error = "cannot resolve '" + host + "': " + (ec ? ec.message() : "no address");
    return std::nullopt;
  }
  const asio::ip::udp::endpoint endpoint = *results.begin();
  asio::ip::udp::socket socket(loop);
  if (socket.open(endpoint.protocol(), ec); ec) {
    error = "cannot open UDP socket: " + ec.message();
    return std::nullopt;
  }
  if (socket.bind(endpoint, ec); ec) {
    error = "cannot bind udp://" + host + ":" + std::to_string(url.port) + ": " + ec.message();
    return std::nullopt;
  }
  return socket;
}

}  // namespace mocaplink::io

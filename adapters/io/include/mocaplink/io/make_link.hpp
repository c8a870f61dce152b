// Link URLs → Links (DESIGN.md "Link URLs"): the one place that knows which io::Link class serves
// each config::LinkKind, as the source registry is for source URLs.
#pragma once

#include <memory>

#include <asio/io_context.hpp>

#include "mocaplink/config/link_url.hpp"
#include "mocaplink/io/link.hpp"

namespace mocaplink::io {

/// Builds (does not start) the link `url` names, run on `loop`: udp:// → UdpLink, udpin:// →
/// UdpInLink, tcp:// → TcpLink, tcpin:// → TcpInLink, serial:// → SerialLink (ros2:// is not
/// an io link: adapters/ros2's make_px4_link builds it). Never fails: a link
/// that cannot open shows it in its state.
[[nodiscard]] std::unique_ptr<Link> make_link(asio::io_context& loop, const config::LinkUrl& url,
                                              LinkOptions options);

}  // namespace mocaplink::io

#include "mocaplink/io/make_link.hpp"

#include <cassert>
#include <utility>

#include "mocaplink/io/link_serial.hpp"
#include "mocaplink/io/link_tcp.hpp"
#include "mocaplink/io/link_tcp_in.hpp"
#include "mocaplink/io/link_udp.hpp"
#include "mocaplink/io/link_udp_in.hpp"

namespace mocaplink::io {

std::unique_ptr<Link> make_link(asio::io_context& loop, const config::LinkUrl& url,
                                LinkOptions options) {
  switch (url.kind) {
    case config::LinkKind::udp:
      return std::make_unique<UdpLink>(loop, url.address.host, url.address.port, std::move(options),
                                       url.bind);
    case config::LinkKind::udpin:
      return std::make_unique<UdpInLink>(loop, url.address.host, url.address.port,
                                         std::move(options));
    case config::LinkKind::tcp:
      return std::make_unique<TcpLink>(loop, url.address.host, url.address.port,
                                       std::move(options));
    case config::LinkKind::tcpin:
      return std::make_unique<TcpInLink>(loop, url.address.host, url.address.port,
                                         std::move(options));
    case config::LinkKind::serial:
      break;
    case config::LinkKind::ros2:  // adapters/ros2 makes these (ros2::make_px4_link)
      assert(false && "a ros2:// link is made by ros2::make_px4_link");
      break;
  }
  return std::make_unique<SerialLink>(loop, url.device, url.baud, std::move(options));
}

}  // namespace mocaplink::io

#include "run_links.hpp"

#include "mocaplink/io/link_serial.hpp"
#include "mocaplink/io/link_tcp.hpp"
#include "mocaplink/io/link_udp.hpp"

namespace mocaplink::app {

VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle) {
  io::LinkOptions options;
  options.name = vehicle.name;
  if (vehicle.signing_key) options.verify_key = mavlink::SigningKey(*vehicle.signing_key);
  VehicleLink out;
  out.vehicle = vehicle;
  out.signing = vehicle.signing_key.has_value();
  const auto& url = vehicle.link;
  switch (url.kind) {
    case config::LinkKind::udp:
      out.link = std::make_unique<io::UdpLink>(loop, url.address.host, url.address.port,
                                               std::move(options));
      break;
    case config::LinkKind::tcp:
      out.link = std::make_unique<io::TcpLink>(loop, url.address.host, url.address.port,
                                               std::move(options));
      break;
    case config::LinkKind::serial:
      out.link = std::make_unique<io::SerialLink>(loop, url.device, url.baud, std::move(options));
      break;
  }
  return out;
}

}  // namespace mocaplink::app

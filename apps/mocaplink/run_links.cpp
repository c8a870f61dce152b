#include "run_links.hpp"

#include <spdlog/spdlog.h>

#include "mocaplink/io/link_serial.hpp"
#include "mocaplink/io/link_tcp.hpp"
#include "mocaplink/io/link_udp.hpp"
#include "run_config.hpp"

namespace mocaplink::app {

VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle) {
  io::LinkOptions options;
  options.name = vehicle.name;
  if (vehicle.signing_key) options.verify_key = mavlink::SigningKey(*vehicle.signing_key);
  VehicleLink out;
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
    case config::LinkKind::serial: {
      const double needed = profile_bytes_per_second(vehicle);
      const double available = io::serial_bytes_per_second(url.baud);
      if (needed > available) {
        // autopilots.md §7: a full ODOMETRY frame is 245 bytes; 57600 baud carries ~23/s.
        spdlog::warn(
            "vehicle {}: profile {} at {:g} Hz needs up to {:.0f} bytes/s but {} baud carries "
            "{:.0f}: frames will be dropped; lower rate_hz or raise the baud rate",
            vehicle.name, config::to_string(vehicle.profile), vehicle.rate_hz, needed, url.baud,
            available);
      }
      out.link = std::make_unique<io::SerialLink>(loop, url.device, url.baud, std::move(options));
      break;
    }
  }
  return out;
}

}  // namespace mocaplink::app

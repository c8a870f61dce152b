#include "run_links.hpp"

#include <spdlog/spdlog.h>

#include "mocaplink/io/link_serial.hpp"
#include "mocaplink/io/make_link.hpp"
#include "run_config.hpp"

namespace mocaplink::app {

VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle) {
  io::LinkOptions options;
  options.name = vehicle.name;
  if (vehicle.signing_key) options.verify_key = mavlink::SigningKey(*vehicle.signing_key);
  VehicleLink out;
  out.vehicle = vehicle;
  out.signing = vehicle.signing_key.has_value();
  const auto& url = vehicle.link;
  if (url.kind == config::LinkKind::serial) {
    // Seam: profile_bytes_per_second (run_config) is the core's profile table's business (issue
    // 11, part M moves it there); once it is, this warning can come from the config checker.
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
  }
  out.link = io::make_link(loop, url, std::move(options));
  return out;
}

}  // namespace mocaplink::app

#include "run_links.hpp"

#include "mocaplink/io/make_link.hpp"

namespace mocaplink::app {

VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle) {
  io::LinkOptions options;
  options.name = vehicle.spec.name;
  options.vehicle_system_id = vehicle.spec.system_id;  // a udpin:// link follows only the vehicle
  if (vehicle.spec.signing_key) options.verify_key = mavlink::SigningKey(*vehicle.spec.signing_key);
  VehicleLink out;
  out.signing = vehicle.spec.signing_key.has_value();
  out.link = io::make_link(loop, vehicle.link, std::move(options));
  return out;
}

}  // namespace mocaplink::app

#include "run_links.hpp"

#include "mocaplink/io/make_link.hpp"
#include "mocaplink/ros2/px4_link.hpp"

namespace mocaplink::app {

VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle,
                              const std::optional<Ros2Graph>& ros2) {
  io::LinkOptions options;
  options.name = vehicle.spec.name;
  options.vehicle_system_id = vehicle.spec.system_id;  // a udpin:// link follows only the vehicle
  if (vehicle.spec.signing_key) options.verify_key = mavlink::SigningKey(*vehicle.spec.signing_key);
  VehicleLink out;
  out.signing = vehicle.spec.signing_key.has_value();
  if (vehicle.link.kind == config::LinkKind::ros2) {
    const Ros2Graph graph = ros2.value_or(Ros2Graph{0, "loopback"});
    out.link =
        ros2::make_px4_link(loop,
                            ros2::Px4LinkSettings{vehicle.link.ros2_namespace, graph.domain_id,
                                                  graph.network_interface, vehicle.spec.system_id},
                            std::move(options));
  } else {
    out.link = io::make_link(loop, vehicle.link, std::move(options));
  }
  return out;
}

}  // namespace mocaplink::app

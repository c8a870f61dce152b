#include "mocaplink/config/demo.hpp"

namespace mocaplink::config {

Config demo_config() {
  Config config;
  config.mocap.source = SourceUrl{"sim://", "sim"};
  // The original ViconMAVLink's default origin (Urbana, IL), kept so demo logs compare directly.
  config.origin = core::GeodeticPosition{40.1156786, -88.2243507, 222.196};
  Vehicle demo;
  demo.spec.name = "demo";
  demo.spec.body = "Body1";
  demo.link = parse_link_url("udp://127.0.0.1:14550").value();
  demo.spec.system_id = 1;
  demo.spec.profile = core::Profile::px4;
  config.vehicles.push_back(demo);
  return config;
}

}  // namespace mocaplink::config

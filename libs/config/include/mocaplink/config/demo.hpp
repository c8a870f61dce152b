// The configuration `mocaplink run` uses when given no arguments (DESIGN.md "Command line").
#pragma once

#include "mocaplink/config/config.hpp"

namespace mocaplink::config {

/// sim:// source (3 bodies at 200 Hz, 0.3 mm noise, z up, x north), one vehicle "demo" following
/// Body1 over udp://127.0.0.1:14550 (QGroundControl's / SITL's default GCS port) with profile px4
/// at 50 Hz, system id 1, dashboard on 127.0.0.1:8080, and the original ViconMAVLink origin in
/// Urbana, IL (40.1156786°, −88.2243507°, 222.196 m).
[[nodiscard]] Config demo_config();

}  // namespace mocaplink::config

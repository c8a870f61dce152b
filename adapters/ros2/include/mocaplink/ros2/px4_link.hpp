// A vehicle reached through PX4's uXRCE-DDS bridge (docs/ros2.md "PX4 over uXRCE-DDS"): the link
// of `link = "ros2://NAMESPACE"`. To the vehicle's code it is a MAVLink link like the others; on
// the ROS 2 graph it speaks PX4's topics through the process's DDS participant (one for all).
//
//   out  ODOMETRY (the `px4` profile's poses) → VehicleOdometry on
//        /NAMESPACE/fmu/in/vehicle_visual_odometry, field by field (wire/px4_messages.hpp), with
//        timestamp_sample the pose's capture time on this host's wall clock and timestamp the send
//        time (PX4 maps both through its time sync with the Agent's host and never lets them lie
//        in its future) while PX4's sync is right, judged from the stamps of what PX4 sends
//        (core/dds_time_sync.hpp); otherwise both 0, which PX4 stamps on arrival (clock()).
//        Every other MAVLink message (heartbeat, TIMESYNC, parameter and stream requests) has no
//        DDS counterpart and is not sent.
//   in   /NAMESPACE/fmu/out/vehicle_status (v1.14, v1.15) or vehicle_status_v1 (v1.16+) →
//        HEARTBEAT: autopilot PX4, the armed flag, the flight mode as PX4's custom_mode;
//        /NAMESPACE/fmu/out/vehicle_odometry → ATTITUDE and LOCAL_POSITION_NED, what the agreement
//        check compares with the mocap pose. Their time_boot_ms is the vehicle's boot time where
//        the sample carries it (a timestamp under 10^15 µs), otherwise the time since the link
//        first heard it after a silence of more than 3 s (PX4 has synced its timestamps to the
//        Agent's clock): the agreement check waits its settling time after each.
//        These frames carry the vehicle's system id and component 1, and go through the link's
//        parser like any received frame.
//
// Transport state: connecting until the participant and the writer exist, then up (whether a
// PX4 listens shows in the heartbeat, as on UDP); down with the reason when DDS refused them.
// Threading: as io::Link; DDS callbacks hand their samples to the link's io_context.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <asio/io_context.hpp>

#include "mocaplink/io/link.hpp"

namespace mocaplink::ros2 {

struct Px4LinkSettings {
  std::string ns;                 ///< PX4's namespace ("" for none, "px4_1" for SITL instance 1)
  std::uint32_t domain_id = 0;    ///< resolved: [ros2] domain_id, ROS_DOMAIN_ID or 0
  std::string network_interface;  ///< [ros2] interface
  std::uint8_t system_id = 1;     ///< stamped on the frames made from PX4's topics
};

/// The DDS topic names of a namespace ("rt/px4_1/fmu/in/vehicle_visual_odometry").
[[nodiscard]] std::string px4_topic(const std::string& ns, const std::string& direction,
                                    const std::string& name);

/// Never null; a participant that cannot start shows as the link's state (down, with why).
[[nodiscard]] std::unique_ptr<io::Link> make_px4_link(asio::io_context& loop,
                                                      const Px4LinkSettings& settings,
                                                      io::LinkOptions options);

}  // namespace mocaplink::ros2

// The bodies on ROS 2 topics over DDS (docs/ros2.md): one DDS participant, per body
// /NS/BODY/pose (geometry_msgs/PoseStamped) and /NS/BODY/odom (nav_msgs/Odometry), every body on
// /tf (tf2_msgs/TFMessage), stamped with the frame's capture time on this host's wall clock.
//
// Off the pose path: the event loop hands each frame's published bodies over with publish(),
// which only moves them into a bounded queue (the oldest frame is dropped, and counted, when the
// publishing thread falls behind); that thread converts them to ROS's frames, encodes them and
// writes them to DDS. A participant that cannot start is an error in status(), never a stop.
//
// Built with Fast DDS where the platform has it (Debian's libfastrtps-dev); elsewhere (Windows)
// available() is false and start() says so.
// Thread-safety: publish() from one thread (the loop); status() from any thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/core/axis_mapping.hpp"
#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/ros.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::ros2 {

/// Whether this build can publish to ROS 2 (false: compiled without a DDS library).
[[nodiscard]] bool available();
/// The DDS library this build publishes with ("Fast DDS 2.9.1"), or why there is none.
[[nodiscard]] std::string implementation();

struct Ros2Options {
  config::Ros2Settings settings;  ///< the checked [ros2] table (its domain_id is not read here)
  std::uint32_t domain_id = 0;    ///< resolved: [ros2] domain_id, ROS_DOMAIN_ID or 0
  core::WorldAxisMapping world;   ///< [mocap] up / north: what RosAxes::mocap undoes
};

/// One body of one frame, as the Bridge tracked it.
struct BodyUpdate {
  std::string name;  ///< the mocap body name (mapped to a ROS token by the publisher)
  core::BodyEstimate estimate;
  core::BodyAxisMapping axes;  ///< the body axes its estimate was made with
};

/// One frame's published bodies.
struct FrameUpdate {
  core::HostTime capture{};  ///< the frame's capture time on the host clock
  std::vector<BodyUpdate> bodies;
};

struct TopicStatus {
  std::string name;               ///< the ROS topic ("/mocap/Quad1/pose")
  std::string type;               ///< the ROS type ("geometry_msgs/msg/PoseStamped")
  std::uint32_t subscribers = 0;  ///< readers matched now
  std::uint64_t published = 0;    ///< samples written
};

struct Ros2Status {
  bool running = false;  ///< the participant is up
  std::string error;     ///< why it is not (or the latest write error), "" when fine
  std::uint32_t domain_id = 0;
  std::string network_interface;
  std::string implementation;
  std::vector<TopicStatus> topics;     ///< in the order they were created
  std::uint64_t frames_published = 0;  ///< frames whose samples were written
  std::uint64_t frames_dropped = 0;    ///< frames dropped because the thread was behind
  std::uint64_t write_errors = 0;      ///< samples DDS refused
  std::vector<std::string> unnamed;    ///< bodies with no ROS name (nothing left of the name)
  /// "A (as B)": bodies not published because their ROS name is another body's.
  std::vector<std::string> clashes;
};

class Publisher {
 public:
  virtual ~Publisher() = default;
  /// Hands one frame over (never blocks on DDS). Frames with no body are ignored.
  virtual void publish(FrameUpdate frame) = 0;
  [[nodiscard]] virtual Ros2Status status() const = 0;
};

/// Starts the participant and the publishing thread. Never null: a participant that cannot
/// start gives a Publisher whose status() has running == false and the error (and which drops
/// what it is given), so the vehicles go on unaffected.
[[nodiscard]] std::unique_ptr<Publisher> start_publisher(const Ros2Options& options);

}  // namespace mocaplink::ros2

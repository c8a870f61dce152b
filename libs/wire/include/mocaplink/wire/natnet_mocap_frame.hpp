// NatNet frames ↔ core::MocapFrame (/work/shared/protocols/natnet.md §3.4, §4, §5, §7).
//
// Client side: the rigid-body table from the model definitions (type-1 datasets only; a name
// given to two ids is ambiguous and its bodies are dropped) and the mapping of a frame through it:
// bodies by name in frame order, tracked = tracking-valid bit and a finite pose with a unit
// quaternion (±0.01), positions in metres in Motive's own world (Y-up unless Motive's Up Axis says
// otherwise: the configured axis mapping handles it), capture_time = mid-exposure ticks / clock
// (3.0+; the software timestamp before), source_latency = (transmit − mid-exposure) / clock.
//
// Server side (the emulator): stable ids per body name for the server's lifetime, the model list
// of the current frame, and a z-up MocapFrame turned into a NatNet frame (optionally into Motive's
// default Y-up world: (x, y, z) → (x, z, −y)). Pure; thread-safe per object.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/wire/natnet_packet.hpp"

namespace mocaplink::wire::natnet {

/// Rigid-body id → name, from one NAT_MODELDEF.
struct BodyTable {
  std::map<std::int32_t, std::string> names;
  std::set<std::string> ambiguous;  ///< names given to more than one id (bodies dropped)
};

[[nodiscard]] BodyTable body_table(const ModelDefinitions& defs);

struct MappedFrame {
  core::MocapFrame frame;
  std::size_t unknown_ids = 0;    ///< bodies whose id is not in the table (not delivered)
  std::size_t invalid_poses = 0;  ///< valid bit set but non-finite / non-unit pose: untracked
};

/// One frame through the table; `clock_hz` from the server info (0 = unknown).
[[nodiscard]] MappedFrame to_mocap_frame(const FrameOfData& frame, const BodyTable& table,
                                         std::uint64_t clock_hz);

/// z-up (x, y, z) → Motive's default Y-up world (x, z, −y), for positions and rotations.
[[nodiscard]] Eigen::Vector3d z_up_to_y_up(const Eigen::Vector3d& p);
[[nodiscard]] Eigen::Quaterniond z_up_to_y_up(const Eigen::Quaterniond& q);

/// The emulator's view of its bodies: ids assigned in order of first appearance (1, 2, …) and
/// kept; the model list is the set of bodies of the latest frame.
class ServedModels {
 public:
  /// `frame` (z-up, metres) as a NatNet frame; `y_up` converts to Motive's Y-up world;
  /// `clock_hz` > 0 sets the tick timestamps from capture_time and source_latency. Sets
  /// kParamModelsChanged when the body list differs from the previous frame's, or, on the first
  /// frame, from the empty list that definitions() described before it.
  [[nodiscard]] FrameOfData frame_of(const core::MocapFrame& frame, bool y_up,
                                     std::uint64_t clock_hz);
  /// The model definitions of the current body list (rigid bodies only, no markers); empty
  /// before the first frame.
  [[nodiscard]] ModelDefinitions definitions();

 private:
  std::map<std::string, std::int32_t> ids_;
  std::vector<std::string> current_;
  /// A client may hold current_: a frame carried it, or definitions() described it (the empty
  /// list before the first frame). Only a change from a list someone holds is flagged.
  bool listed_ = false;
};

}  // namespace mocaplink::wire::natnet

#include "mocaplink/wire/vicon_protocol.hpp"

namespace mocaplink::wire::vicon {

ItemClass item_class(std::uint32_t type) {
  switch (static_cast<ItemType>(type)) {
    // §4 class "St".
    case ItemType::stream_info:
    case ItemType::subject_info:
    case ItemType::subject_topology:
    case ItemType::subject_scale:
    case ItemType::subject_health:
    case ItemType::application_info:
    case ItemType::object_quality:
      return ItemClass::static_item;
    // §4 class "Dy" (the types the SDK copies forward when listed unchanged, §7 step 2).
    case ItemType::frame_info:
    case ItemType::hardware_frame_info:
    case ItemType::timecode:
    case ItemType::latency_info:
    case ItemType::frame_rate_info:
    case ItemType::global_segments:
    case ItemType::local_segments:
    case ItemType::lightweight_segments:
    case ItemType::labeled_recons:
    case ItemType::unlabeled_recons:
    case ItemType::labeled_recon_ray_assignments:
      return ItemClass::dynamic_item;
    case ItemType::object_enums:
    case ItemType::request_frame:
    case ItemType::keep_alive:
    case ItemType::contents:
    case ItemType::start_multicast_sender:
    case ItemType::stop_multicast_sender:
    case ItemType::filter:
    case ItemType::request_next_frame:
    case ItemType::ping:
    case ItemType::apex_haptics:
      return ItemClass::control;
  }
  return ItemClass::unknown;
}

std::string item_type_name(std::uint32_t type) {
  switch (static_cast<ItemType>(type)) {
    case ItemType::stream_info:
      return "StreamInfo";
    case ItemType::subject_info:
      return "SubjectInfo";
    case ItemType::frame_info:
      return "FrameInfo";
    case ItemType::labeled_recons:
      return "LabeledRecons";
    case ItemType::unlabeled_recons:
      return "UnlabeledRecons";
    case ItemType::local_segments:
      return "LocalSegments";
    case ItemType::global_segments:
      return "GlobalSegments";
    case ItemType::timecode:
      return "Timecode";
    case ItemType::labeled_recon_ray_assignments:
      return "LabeledReconRayAssignments";
    case ItemType::latency_info:
      return "LatencyInfo";
    case ItemType::subject_topology:
      return "SubjectTopology";
    case ItemType::subject_health:
      return "SubjectHealth";
    case ItemType::apex_haptics:
      return "ApexHaptics";
    case ItemType::hardware_frame_info:
      return "HardwareFrameInfo";
    case ItemType::application_info:
      return "ApplicationInfo";
    case ItemType::frame_rate_info:
      return "FrameRateInfo";
    case ItemType::object_quality:
      return "ObjectQuality";
    case ItemType::ping:
      return "Ping";
    case ItemType::lightweight_segments:
      return "LightweightSegments";
    case ItemType::subject_scale:
      return "SubjectScale";
    case ItemType::object_enums:
      return "ObjectEnums";
    case ItemType::request_frame:
      return "RequestFrame";
    case ItemType::keep_alive:
      return "KeepAlive";
    case ItemType::contents:
      return "Contents";
    case ItemType::start_multicast_sender:
      return "StartMulticastSender";
    case ItemType::stop_multicast_sender:
      return "StopMulticastSender";
    case ItemType::filter:
      return "Filter";
    case ItemType::request_next_frame:
      return "RequestNextFrame";
  }
  return "type " + std::to_string(type);
}

}  // namespace mocaplink::wire::vicon

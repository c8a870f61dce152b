// The DDS library behind the publisher and the PX4 links (internal to adapters/ros2): a
// participant that makes writers and readers of opaque, already encoded XCDR1 samples under any
// type name. dds_fastdds.cpp is the one implementation; dds_none.cpp stands in where the platform
// has no DDS package. shared_participant() gives every user in the process the one participant
// of its domain and interface.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

namespace mocaplink::ros2::detail {

struct ParticipantSettings {
  std::uint32_t domain_id = 0;
  std::string network_interface = "all";  ///< "all", "loopback" or an IPv4 address
  std::string name = "mocaplink";
};

struct WriterSettings {
  std::string topic;                   ///< the DDS topic ("rt/mocap/Quad1/pose")
  std::string type;                    ///< the DDS type ("geometry_msgs::msg::dds_::PoseStamped_")
  std::uint32_t depth = 10;            ///< keep-last history
  std::uint32_t max_sample_bytes = 0;  ///< the largest encoded sample, header included
  /// Called from a DDS thread whenever the number of matched readers changes (the new count).
  std::function<void(std::uint32_t)> on_matched;
};

struct ReaderSettings {
  std::string topic;  ///< the DDS topic ("rt/px4_1/fmu/out/vehicle_status")
  std::string type;   ///< the DDS type ("px4_msgs::msg::dds_::VehicleStatus_")
  std::uint32_t depth = 10;
  std::uint32_t max_sample_bytes = 0;
  /// Called from a DDS thread with each sample (encapsulation header first; valid during the
  /// call only).
  std::function<void(std::span<const std::uint8_t>)> on_sample;
};

/// Destroying a reader stops its callbacks (the destructor waits for one that runs).
class Reader {
 public:
  virtual ~Reader() = default;
};

class Writer {
 public:
  virtual ~Writer() = default;
  /// One encoded sample (encapsulation header first). False when DDS refused it.
  virtual bool write(std::span<const std::uint8_t> sample) = 0;
};

class Participant {
 public:
  virtual ~Participant() = default;
  /// A reliable, volatile, keep-last writer; nullptr and `error` when DDS refused it.
  virtual std::unique_ptr<Writer> make_writer(const WriterSettings& settings,
                                              std::string& error) = 0;
  /// A best-effort, volatile, keep-last reader (it matches reliable and best-effort writers, as
  /// PX4's Agent-made ones are); nullptr and `error` when DDS refused it.
  virtual std::unique_ptr<Reader> make_reader(const ReaderSettings& settings,
                                              std::string& error) = 0;
};

/// nullptr and `error` when the participant cannot start (no such interface, ports in use, no
/// DDS in this build).
[[nodiscard]] std::unique_ptr<Participant> make_participant(const ParticipantSettings& settings,
                                                            std::string& error);
/// The process's participant for these settings: made at the first call, shared while anyone
/// holds it (the publisher and every ros2:// link: one participant on the graph).
[[nodiscard]] std::shared_ptr<Participant> shared_participant(const ParticipantSettings& settings,
                                                              std::string& error);
[[nodiscard]] bool dds_available();
[[nodiscard]] std::string dds_implementation();

}  // namespace mocaplink::ros2::detail

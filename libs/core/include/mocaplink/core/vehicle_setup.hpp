// VehicleSetup: reads the parameters a vehicle's profile depends on, says which are wrong and
// why, and writes the fixes only when asked (issue 28; rules in setup_rules.hpp). Also keeps what
// the vehicle says about itself: its autopilot and version, its last STATUSTEXTs ("PreArm: ..."),
// its estimator's health. Pure: time is passed in; one per vehicle, owned by the Bridge.
//
// Exchange (MAVLink "Parameter Protocol", "Command Protocol"), per boot of the vehicle:
//   waiting      no heartbeat from the vehicle yet. Nothing is sent.
//   identifying  AUTOPILOT_VERSION asked for with MAV_CMD_REQUEST_MESSAGE(148), every
//                kSetupRetryPeriod, at most kVersionAttempts times. The family (PX4, ArduPilot)
//                comes from the heartbeat; the version decides renamed parameters (EKF2_AID_MASK
//                up to PX4 1.13, GPS_TYPE up to ArduPilot 4.5). No answer: the newest rules.
//   reading      PARAM_REQUEST_READ by name (param_index −1) for each rule's parameter, ONE in
//                flight at a time and at least kParamGap apart (a 57600-baud radio carries ~170
//                such requests a second; this uses ~10), retried every kSetupRetryPeriod, at most
//                kParamAttempts times; a parameter never answered is `missing`.
//   ready        every parameter answered or given up, nothing blocks.
//   blocked      at least one item blocks (severity blocks and status wrong or missing).
//   no_answer    not one parameter answered: the link carries no parameter protocol (a router
//                that filters it, a port without MAVLink, a vehicle busy booting).
//   unsupported  not PX4 or ArduPilot: there are no rules.
//   unavailable  the vehicle's link carries no parameters (VehicleLink::px4_dds, PX4 over
//                uXRCE-DDS): nothing is asked or written; the list shows the rules of the newest
//                firmware as `unread`, to be checked over a MAVLink link (unavailable_reason()).
// Any PARAM_VALUE for a parameter of the list updates it at any time (a ground station that
// changes it makes the vehicle announce the new value), and so does the answer to our own write.
// A vehicle that goes silent and comes back, or reboots (the caller says so), is read again.
//
// Values: PARAM_VALUE carries a float. Integer parameters are either the integer's bytes in the
// float (PX4: MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE) or the integer converted to float
// (ArduPilot: PARAM_ENCODE_C_CAST); AUTOPILOT_VERSION.capabilities says which, and without it the
// family does. A PARAM_VALUE with an unknown param_type, or a float that is not finite, is
// malformed: counted and ignored.
//
// Apply (only ever on request, apply()): refused while the vehicle is armed, while reading, or
// when a named parameter is not a wrong item with a fix in the list as it stands — the operator
// names what they saw, and nothing else is written. Each fix is a PARAM_SET, one in flight,
// retried every kSetupRetryPeriod up to kParamAttempts times, confirmed by the PARAM_VALUE that
// comes back: the same value → confirmed; another → failed, with the value the vehicle kept; no
// answer → failed. Arming stops the remaining writes. Items whose parameter takes effect after a
// reboot say so; reboot() is separate (MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN, refused while armed).
// Not thread-safe (one owner).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/core/profile.hpp"
#include "mocaplink/core/setup_rules.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::core {

inline constexpr Duration kSetupRetryPeriod = std::chrono::seconds(1);
inline constexpr Duration kParamGap = std::chrono::milliseconds(100);
inline constexpr std::uint8_t kParamAttempts = 3;
inline constexpr std::uint8_t kVersionAttempts = 3;
/// STATUSTEXTs kept per vehicle (the newest).
inline constexpr std::size_t kStatusTextKeep = 8;

enum class SetupState : std::uint8_t {
  waiting,
  identifying,
  reading,
  ready,
  blocked,
  no_answer,
  unsupported,
  unavailable
};
/// "waiting", "identifying", "reading", "ready", "blocked", "no answer", "unsupported",
/// "unavailable".
[[nodiscard]] std::string_view to_string(SetupState state);

enum class ApplyState : std::uint8_t { none, pending, confirmed, failed };
/// "none", "pending", "confirmed", "failed".
[[nodiscard]] std::string_view to_string(ApplyState state);

/// What a vehicle's link carries (docs/ros2.md "PX4 over uXRCE-DDS").
enum class VehicleLink : std::uint8_t {
  mavlink,  ///< MAVLink both ways: every request, answer and command
  /// PX4's uXRCE-DDS topics through the Agent (adapters/ros2 px4_link.hpp): the poses out;
  /// in, its status (as HEARTBEAT) and its estimate (as ATTITUDE, LOCAL_POSITION_NED). No
  /// parameters, commands, TIMESYNC, origin or heartbeat of ours: the Bridge sends it none.
  px4_dds,
};

/// Why the set-up list of a vehicle on `link` cannot be read ("" for a MAVLink link): the sentence
/// of the log, `setup.note` and `vehicle setup`.
[[nodiscard]] std::string_view unavailable_reason(VehicleLink link);

/// One line of the list with what Apply did to it.
struct SetupLine {
  SetupItem item;
  ApplyState apply = ApplyState::none;
  std::string apply_note;  ///< "the vehicle kept 0", "no answer after 3 tries", ...
};

/// MAV_SEVERITY as a word: "emergency" ... "debug".
[[nodiscard]] std::string_view severity_name(std::uint8_t severity);

struct StatusText {
  HostTime time{};
  std::uint8_t severity = 6;
  std::string text;  ///< printable ASCII (anything else shown as '?')
};

/// The estimator's own report (EKF_STATUS_REPORT on ArduPilot, ESTIMATOR_STATUS on PX4), in
/// words.
struct EstimatorHealth {
  std::string_view source;  ///< "EKF_STATUS_REPORT" or "ESTIMATOR_STATUS"
  std::uint32_t flags = 0;
  std::vector<std::string_view> good;      ///< "attitude", "horizontal velocity", ...
  std::vector<std::string_view> problems;  ///< "no horizontal position", "GPS glitch", ...
  HostTime time{};
};
/// Words for EKF_STATUS_REPORT.flags (ArduPilot) and ESTIMATOR_STATUS.flags (PX4).
[[nodiscard]] EstimatorHealth describe_ekf_status(std::uint16_t flags);
[[nodiscard]] EstimatorHealth describe_estimator_status(std::uint16_t flags);

/// The delay recommendation (autopilots.md §4).
struct SetupDelay {
  std::optional<double> measured_ms;     ///< capture → the vehicle
  std::optional<double> recommended_ms;  ///< for the parameter below
  std::string parameter;                 ///< EKF2_EV_DELAY, VISO_DELAY_MS, GPS1_DELAY_MS...
  std::optional<double> current_ms;
  std::string basis;  ///< how it was measured, one sentence
};

/// What the caller measures for the delay: capture → processed (median, ms; the mocap system's
/// latency where its protocol reports it, plus the transport to mocaplink), and the link's
/// round trip from our TIMESYNC requests.
struct DelayInputs {
  std::optional<double> capture_age_ms;
  std::optional<double> link_rtt_ms;
  bool vehicle_timesync = false;  ///< the vehicle sends TIMESYNC requests (we answer them)
  /// PX4 over uXRCE-DDS, sent capture stamps: it converts them with its own time sync to the
  /// Agent host's clock (protocols/ros2-dds.md §4). False on such a link: stamps of 0, which PX4
  /// takes at arrival (core/dds_time_sync.hpp).
  bool dds_time_sync = false;
};

/// The vehicle as the heartbeat describes it, given on every tick.
struct SetupTarget {
  bool alive = false;
  std::uint8_t autopilot = 0;  ///< MAV_AUTOPILOT
  std::uint8_t compid = 1;     ///< the heartbeat's component: the target of requests
  bool armed = false;
};

struct VehicleSetupCounters {
  std::uint64_t param_requests = 0;  ///< PARAM_REQUEST_READ sent
  std::uint64_t param_values = 0;    ///< PARAM_VALUE received for a parameter of the list
  std::uint64_t param_sets = 0;      ///< PARAM_SET sent
  std::uint64_t malformed = 0;       ///< PARAM_VALUE with an unknown type or a non-finite float
  std::uint64_t version_requests = 0;
};

struct VehicleSetupSnapshot {
  SetupState state = SetupState::waiting;
  AutopilotFamily autopilot = AutopilotFamily::unknown;
  std::optional<FirmwareVersion> version;
  /// AUTOPILOT_VERSION answered or given up this boot: `version` is what it will be.
  bool identified = false;
  SetupInput input = SetupInput::none;
  std::vector<SetupLine> lines;
  std::vector<StatusText> statustext;  ///< oldest first, at most kStatusTextKeep
  std::optional<EstimatorHealth> estimator;
  bool armed = false;
  std::vector<std::string> reboot_for;  ///< confirmed changes that take effect after a reboot
  SetupDelay delay;
  VehicleSetupCounters counters;
  /// The one-line reason of the last refused apply() / reboot() ("" if none).
  std::string last_refusal;
};

/// What apply() or reboot() did.
struct SetupRequestResult {
  bool accepted = false;
  std::string message;  ///< why not, or what will be written
};

class VehicleSetup {
 public:
  /// `system_id`: the vehicle's; `component_id`: ours. `profile`, `messages`: what is sent to
  /// the vehicle (they decide the rules with its autopilot).
  VehicleSetup(std::uint8_t system_id, std::uint8_t component_id, Profile profile,
               MessageSet messages, VehicleLink link = VehicleLink::mavlink);

  /// A message from the vehicle's link that arrived at `now`; appends log lines to `notes`.
  void on_message(const ReceivedMessage& message, HostTime now, std::vector<std::string>& notes);

  /// Time passes (about every 100 ms): what to send now goes to `out` and log lines to `notes`.
  void on_tick(HostTime now, const SetupTarget& target, const DelayInputs& delay,
               std::vector<mavlink::Message>& out, std::vector<std::string>& notes);

  /// The vehicle rebooted (its boot clock went back): read everything again.
  void on_reboot(HostTime now);

  /// Writes the fixes of the named parameters (see the header comment for the refusals).
  SetupRequestResult apply(std::span<const std::string> parameters, HostTime now);
  /// Asks the autopilot to reboot (refused while armed). The caller sends nothing else for it.
  SetupRequestResult reboot(HostTime now, std::vector<mavlink::Message>& out);

  /// The messages sent to the vehicle changed (the dashboard's message boxes).
  void set_messages(MessageSet messages);

  [[nodiscard]] VehicleSetupSnapshot snapshot() const;
  /// The snapshot's autopilot, version and identified, without building its list (every tick).
  [[nodiscard]] AutopilotFamily autopilot() const { return family_; }
  [[nodiscard]] const std::optional<FirmwareVersion>& version() const { return version_; }
  [[nodiscard]] bool identified() const { return version_done_; }
  [[nodiscard]] SetupState state() const { return state_; }
  /// What the vehicle is fed (setup_input), which decides the rules.
  [[nodiscard]] SetupInput input() const;
  /// A parameter of the list as the vehicle reported it (nullopt: not in the list, not read yet,
  /// or never answered this boot). Used by the agreement check (estimate_sources.hpp).
  [[nodiscard]] std::optional<double> parameter(std::string_view name) const;

 private:
  struct Param {
    std::string name;
    std::optional<double> value;
    std::uint8_t type = 0;  ///< MAV_PARAM_TYPE as the vehicle reported it
    std::uint8_t attempts = 0;
    bool gave_up = false;
    std::optional<double> writing;  ///< queued or in flight: the value to write
    std::uint8_t write_attempts = 0;
    ApplyState apply = ApplyState::none;
    std::string apply_note;
  };

  void restart(HostTime now);
  void choose_rules();
  void on_param_value(const mavlink::ParamValue& value, HostTime now,
                      std::vector<std::string>& notes);
  void on_statustext(const mavlink::Statustext& text, HostTime now,
                     std::vector<std::string>& notes);
  void tick_reads(HostTime now, std::vector<mavlink::Message>& out);
  void tick_writes(HostTime now, std::vector<mavlink::Message>& out,
                   std::vector<std::string>& notes);
  void update_state(std::vector<std::string>& notes);
  [[nodiscard]] bool bytewise() const;
  [[nodiscard]] std::optional<double> decode(const mavlink::ParamValue& value) const;
  [[nodiscard]] float encode(double value, std::uint8_t type) const;
  [[nodiscard]] std::vector<SetupLine> lines() const;
  [[nodiscard]] std::optional<double> recommended_delay() const;
  [[nodiscard]] const SetupRule* delay_rule() const;
  Param* find(std::string_view name);

  std::uint8_t system_id_;
  std::uint8_t component_id_;
  Profile profile_;
  MessageSet messages_;
  VehicleLink link_;
  SetupTarget target_{};
  SetupState state_ = SetupState::waiting;
  AutopilotFamily family_ = AutopilotFamily::unknown;
  std::optional<FirmwareVersion> version_;
  std::optional<std::uint64_t> capabilities_;
  std::uint8_t version_attempts_ = 0;
  bool version_done_ = false;
  std::optional<HostTime> next_send_;   ///< the earliest next request (kParamGap, retries)
  std::optional<std::size_t> reading_;  ///< index into params_ of the read in flight
  std::optional<std::size_t> writing_;  ///< index into params_ of the write in flight
  std::vector<const SetupRule*> rules_;
  std::vector<Param> params_;
  std::deque<StatusText> statustext_;
  std::optional<EstimatorHealth> estimator_;
  DelayInputs delay_{};
  std::vector<std::string> reboot_for_;
  std::string last_refusal_;
  bool reboot_asked_ = false;  ///< a reboot was asked and its COMMAND_ACK has not come yet
  VehicleSetupCounters counters_;
  SetupState announced_ = SetupState::waiting;  ///< the state last logged
};

}  // namespace mocaplink::core

// VehicleStreams (vehicle_streams.hpp): asks for ATTITUDE, LOCAL_POSITION_NED, the estimator's
// health and a compass field (RAW_IMU, HIGHRES_IMU), confirms, retries, falls back to
// REQUEST_DATA_STREAM on ArduPilot, asks again after a reboot.
#include "mocaplink/core/vehicle_streams.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mocaplink/core/message_builders.hpp"
#include "mocaplink/mavlink/enums.hpp"

namespace mocaplink::core {
namespace {

constexpr std::uint16_t kSetMessageInterval = 511;  // MAV_CMD_SET_MESSAGE_INTERVAL
constexpr std::uint8_t kResultAccepted = 0;
constexpr std::uint8_t kResultTemporarilyRejected = 1;
constexpr std::uint8_t kResultInProgress = 5;

std::string result_name(std::uint8_t result) {
  const std::string_view name = mavlink::to_string(static_cast<mavlink::MavResult>(result));
  return name.empty() ? "MAV_RESULT " + std::to_string(result) : std::string(name);
}

std::string rate_text(VehicleStream stream) {
  char text[64];
  std::snprintf(text, sizeof text, "%g Hz", rate_hz(stream));
  return text;
}

/// "the vehicle refused SET_MESSAGE_INTERVAL for ATTITUDE (MAV_RESULT_DENIED)", or that it never
/// answered.
std::string refusal(VehicleStream stream, const std::optional<std::uint8_t>& ack_result,
                    std::uint8_t autopilot) {
  const std::string name(mavlink_name(stream, autopilot));
  if (ack_result) {
    return "the vehicle refused SET_MESSAGE_INTERVAL for " + name + " (" +
           result_name(*ack_result) + ")";
  }
  return "the vehicle never answered SET_MESSAGE_INTERVAL for " + name + " (" +
         std::to_string(kCommandAttempts) + " tries)";
}

std::int64_t ms_of(Duration d) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

/// Everything about one asked-for message, in one place.
struct StreamFacts {
  std::string_view name;
  std::uint32_t id;
  std::uint8_t data_stream;  ///< ArduPilot's MAV_DATA_STREAM group carrying it
  std::string_view data_stream_name;
};

StreamFacts facts(VehicleStream stream, std::uint8_t autopilot) {
  switch (stream) {
    case VehicleStream::attitude:
      return {mavlink::Attitude::kName, mavlink::Attitude::kId, 10, "EXTRA1"};
    case VehicleStream::local_position_ned:
      return {mavlink::LocalPositionNed::kName, mavlink::LocalPositionNed::kId, 6, "POSITION"};
    case VehicleStream::heading:
      // The magnetometer: PX4's in HIGHRES_IMU (PX4 has no groups, never a fallback),
      // ArduPilot's in RAW_IMU, whose group is RAW_SENSORS.
      return autopilot == kMavAutopilotPx4
                 ? StreamFacts{mavlink::HighresImu::kName, mavlink::HighresImu::kId, 1,
                               "RAW_SENSORS"}
                 : StreamFacts{mavlink::RawImu::kName, mavlink::RawImu::kId, 1, "RAW_SENSORS"};
    case VehicleStream::estimator:
      break;
  }
  // EXTRA3 is ArduPilot's group with EKF_STATUS_REPORT; PX4 has no groups (never a fallback).
  return autopilot == kMavAutopilotArdupilot
             ? StreamFacts{mavlink::EkfStatusReport::kName, mavlink::EkfStatusReport::kId, 12,
                           "EXTRA3"}
             : StreamFacts{mavlink::EstimatorStatus::kName, mavlink::EstimatorStatus::kId, 12,
                           "EXTRA3"};
}

}  // namespace

std::string_view mavlink_name(VehicleStream stream, std::uint8_t autopilot) {
  return facts(stream, autopilot).name;
}

std::uint32_t message_id(VehicleStream stream, std::uint8_t autopilot) {
  return facts(stream, autopilot).id;
}

std::uint8_t data_stream_id(VehicleStream stream) {
  return facts(stream, kMavAutopilotArdupilot).data_stream;
}

std::string_view data_stream_name(VehicleStream stream) {
  return facts(stream, kMavAutopilotArdupilot).data_stream_name;
}

bool asked_of(VehicleStream stream, std::uint8_t autopilot) {
  switch (stream) {
    case VehicleStream::estimator:
      return autopilot == kMavAutopilotArdupilot || autopilot == kMavAutopilotPx4;
    case VehicleStream::heading:
      return autopilot == kMavAutopilotArdupilot || autopilot == kMavAutopilotPx4;
    case VehicleStream::attitude:
    case VehicleStream::local_position_ned:
      break;
  }
  return true;
}

double rate_hz(VehicleStream stream) {
  switch (stream) {
    case VehicleStream::estimator:
      return kEstimatorRateHz;
    case VehicleStream::heading:
      return kHeadingRateHz;
    case VehicleStream::attitude:
    case VehicleStream::local_position_ned:
      break;
  }
  return kStreamRateHz;
}

std::int32_t interval_us(VehicleStream stream) {
  return static_cast<std::int32_t>(std::lround(1e6 / rate_hz(stream)));
}

std::string_view to_string(StreamState state) {
  switch (state) {
    case StreamState::idle:
      return "idle";
    case StreamState::asking:
      return "asking";
    case StreamState::accepted:
      return "accepted";
    case StreamState::fallback:
      return "fallback";
    case StreamState::arriving:
      return "arriving";
    case StreamState::refused:
      return "refused";
    case StreamState::silent:
      return "silent";
  }
  return "unknown";
}

std::optional<std::string> describe_missing(VehicleStream stream, const StreamStatus& s,
                                            std::uint8_t autopilot) {
  const std::string name(mavlink_name(stream, autopilot));
  switch (s.state) {
    case StreamState::idle:
      return "waiting for " + name + " from the vehicle";
    case StreamState::asking:
      return "asked the vehicle for " + name + " (SET_MESSAGE_INTERVAL), waiting for its answer";
    case StreamState::accepted:
      return "the vehicle accepted the request for " + name + ", none arrived yet";
    case StreamState::fallback:
      return refusal(stream, s.ack_result, autopilot) + "; asked with REQUEST_DATA_STREAM " +
             std::string(data_stream_name(stream)) + ", none arrived yet";
    case StreamState::arriving:
      return std::nullopt;
    case StreamState::refused:
      return refusal(stream, s.ack_result, autopilot) + ": no " + name +
             (stream == VehicleStream::estimator ? ", so the estimator's flags are unknown"
              : stream == VehicleStream::heading ? ", so the nose cannot be checked"
                                                 : ", so the agreement cannot be checked") +
             " (asked again after a reboot)";
    case StreamState::silent:
      // ArduPilot accepts the request but sends LOCAL_POSITION_NED only once its EKF has an
      // origin (GCS_Common.cpp send_local_position), which took ArduCopter SITL with default
      // parameters 30-40 s: ATTITUDE arriving on the same port says the port is fine.
      if (stream == VehicleStream::local_position_ned) {
        return "no " + name +
               " from the vehicle after asking: it sends none until its estimator has an "
               "origin (a GPS fix, or SET_GPS_GLOBAL_ORIGIN) and a position source (see the "
               "set-up list); if ATTITUDE is missing too, is this port's MAVLink enabled?";
      }
      if (stream == VehicleStream::estimator || stream == VehicleStream::heading) {
        return "no " + name +
               " from the vehicle after asking: its firmware may not send it on this port";
      }
      return "no " + name + " from the vehicle after asking: is this port's MAVLink enabled?";
  }
  return std::nullopt;
}

VehicleStreams::VehicleStreams(std::uint8_t system_id, std::uint8_t component_id)
    : system_id_(system_id), component_id_(component_id) {}

VehicleStreamsSnapshot VehicleStreams::snapshot() const {
  VehicleStreamsSnapshot s;
  for (std::size_t i = 0; i < kVehicleStreamCount; ++i) s.streams[i] = streams_[i].status;
  s.reboots = reboots_;
  return s;
}

void VehicleStreams::on_message(const ReceivedMessage& message, HostTime now,
                                std::vector<std::string>& notes) {
  if (message.sysid != system_id_) return;
  if (const auto* att = std::get_if<mavlink::Attitude>(&message.message)) {
    boot_clock(last_boot_ms_, att->time_boot_ms, now, notes);
    arrived(VehicleStream::attitude, now, notes);
  } else if (const auto* pos = std::get_if<mavlink::LocalPositionNed>(&message.message)) {
    boot_clock(last_boot_ms_, pos->time_boot_ms, now, notes);
    arrived(VehicleStream::local_position_ned, now, notes);
  } else if (std::holds_alternative<mavlink::EkfStatusReport>(message.message) ||
             std::holds_alternative<mavlink::EstimatorStatus>(message.message)) {
    // Either autopilot's: arriving is arriving, whichever was asked for.
    arrived(VehicleStream::estimator, now, notes);
  } else if (std::holds_alternative<mavlink::RawImu>(message.message) ||
             std::holds_alternative<mavlink::HighresImu>(message.message)) {
    arrived(VehicleStream::heading, now, notes);
  } else if (const auto* ack = std::get_if<mavlink::CommandAck>(&message.message)) {
    on_ack(*ack, now, notes);
  } else if (const auto* ts = std::get_if<mavlink::Timesync>(&message.message)) {
    // The vehicle's clock: tc1 of an answer, ts1 of its own request (ns since its boot on PX4 and
    // ArduPilot). Only the autopilot's: another component with our sysid keeps its own clock.
    if (message.compid != target_.compid) return;
    const std::int64_t clock_ns = ts->tc1 != 0 ? ts->tc1 : ts->ts1;
    if (clock_ns > 0) boot_clock(last_timesync_ms_, clock_ns / 1'000'000, now, notes);
  }
}

void VehicleStreams::boot_clock(std::optional<std::int64_t>& last_ms, std::int64_t now_ms,
                                HostTime now, std::vector<std::string>& notes) {
  const bool rebooted = last_ms && now_ms + ms_of(kRebootStepBack) < *last_ms;
  const std::int64_t before_ms = last_ms.value_or(0);
  last_ms = now_ms;
  if (!rebooted) return;
  ++reboots_;
  // The other clock's last value belongs to the previous boot.
  last_boot_ms_.reset();
  last_timesync_ms_.reset();
  last_ms = now_ms;
  for (Stream& s : streams_) s = Stream{};
  in_flight_.reset();
  if (alive_since_) alive_since_ = now;  // a new grace period: its defaults may stream again
  char text[192];
  std::snprintf(text, sizeof text,
                "the vehicle rebooted (its boot clock went back from %.1f s to %.1f s): message "
                "rates it was asked for are lost; asking again for what does not arrive",
                static_cast<double>(before_ms) / 1e3, static_cast<double>(now_ms) / 1e3);
  notes.emplace_back(text);
}

void VehicleStreams::arrived(VehicleStream s, HostTime now, std::vector<std::string>& notes) {
  Stream& stream = at(s);
  stream.status.last_seen = now;
  if (stream.status.state == StreamState::arriving) return;
  stream.status.state = StreamState::arriving;
  stream.deadline.reset();
  if (stream.status.asked) {
    notes.push_back(std::string(mavlink_name(s, target_.autopilot)) + " arriving" +
                    (stream.status.data_stream_requests > 0 ? " (after REQUEST_DATA_STREAM)" : ""));
  }
}

void VehicleStreams::on_ack(const mavlink::CommandAck& ack, HostTime now,
                            std::vector<std::string>& notes) {
  if (ack.command != kSetMessageInterval || !in_flight_) return;
  // Addressed to someone else (a ground station's own SET_MESSAGE_INTERVAL): not ours. The
  // target fields are MAVLink 2 extensions; 0 (absent) is taken as ours.
  if (ack.target_system != 0 && ack.target_system != system_id_) return;
  if (ack.target_component != 0 && ack.target_component != component_id_) return;
  const VehicleStream s = *in_flight_;
  Stream& stream = at(s);
  stream.status.ack_result = ack.result;
  if (ack.result == kResultTemporarilyRejected || ack.result == kResultInProgress) return;
  in_flight_.reset();
  if (stream.status.state != StreamState::asking) return;  // it arrived meanwhile
  if (ack.result == kResultAccepted) {
    stream.status.state = StreamState::accepted;
    stream.deadline = now + kStreamAnswerTimeout;
    notes.push_back("the vehicle accepted SET_MESSAGE_INTERVAL for " +
                    std::string(mavlink_name(s, target_.autopilot)));
  } else {
    give_up(s, now, notes);
  }
}

void VehicleStreams::give_up(VehicleStream s, HostTime now, std::vector<std::string>& notes) {
  Stream& stream = at(s);
  std::string text = refusal(s, stream.status.ack_result, target_.autopilot);
  if (target_.autopilot == kMavAutopilotArdupilot) {
    stream.status.state = StreamState::fallback;
    stream.next_send = now;
    stream.deadline.reset();
    text += "; asking with REQUEST_DATA_STREAM " + std::string(data_stream_name(s)) + " at " +
            rate_text(s) + " instead";
  } else {
    stream.status.state = StreamState::refused;
    stream.next_send.reset();
    text += "; not asked again until the vehicle reboots";
  }
  notes.push_back(std::move(text));
}

void VehicleStreams::on_tick(HostTime now, const StreamTarget& target,
                             std::vector<mavlink::Message>& out, std::vector<std::string>& notes) {
  target_ = target;
  if (!target.alive) {
    alive_since_.reset();  // heard again later: a new grace period before asking
    return;
  }
  if (!alive_since_) alive_since_ = now;
  for (const VehicleStream s : kVehicleStreams) tick_stream(s, now, out, notes);
  tick_command(now, out, notes);
}

void VehicleStreams::tick_stream(VehicleStream s, HostTime now, std::vector<mavlink::Message>& out,
                                 std::vector<std::string>& notes) {
  Stream& stream = at(s);
  StreamStatus& st = stream.status;
  const auto start_round = [&] {
    st.state = StreamState::asking;
    st.attempts = 0;
    st.data_stream_requests = 0;
    st.ack_result.reset();
    stream.deadline.reset();
  };
  switch (st.state) {
    case StreamState::idle:
      if (now - *alive_since_ >= kStreamGrace && asked_of(s, target_.autopilot) &&
          (s != VehicleStream::heading || target_.want_heading)) {
        start_round();
      }
      break;
    case StreamState::arriving:
      // Counted from the heartbeat's return too: a link that was silent gets its chance first.
      // A compass no longer wanted is not asked for again.
      if (s == VehicleStream::heading && !target_.want_heading) break;
      if (st.last_seen && now - std::max(*st.last_seen, *alive_since_) >= kStreamStaleAfter) {
        notes.push_back(std::string(mavlink_name(s, target_.autopilot)) +
                        " stopped arriving; asking again");
        start_round();
      }
      break;
    case StreamState::accepted:
      if (stream.deadline && now >= *stream.deadline) {
        st.state = StreamState::silent;
        notes.push_back(*describe_missing(s, st, target_.autopilot));
      }
      break;
    case StreamState::fallback:
      if (st.data_stream_requests < kDataStreamAttempts) {
        if (stream.next_send && now >= *stream.next_send) {
          ++st.data_stream_requests;
          st.asked = true;
          out.emplace_back(build_request_data_stream(data_stream_id(s),
                                                     static_cast<std::uint16_t>(rate_hz(s)),
                                                     system_id_, target_.compid));
          stream.next_send = now + kCommandRetryPeriod;
          if (st.data_stream_requests == kDataStreamAttempts) {
            stream.deadline = now + kStreamAnswerTimeout;
          }
        }
      } else if (stream.deadline && now >= *stream.deadline) {
        st.state = StreamState::silent;
        notes.push_back(*describe_missing(s, st, target_.autopilot));
      }
      break;
    case StreamState::asking:  // tick_command
    case StreamState::refused:
    case StreamState::silent:
      break;
  }
}

void VehicleStreams::tick_command(HostTime now, std::vector<mavlink::Message>& out,
                                  std::vector<std::string>& notes) {
  if (in_flight_) {
    const VehicleStream s = *in_flight_;
    Stream& stream = at(s);
    if (stream.next_send && now < *stream.next_send) return;
    if (stream.status.state != StreamState::asking) {
      in_flight_.reset();  // it arrived meanwhile; its ACK had its retry period to come
    } else if (stream.status.attempts < kCommandAttempts) {
      out.emplace_back(build_set_message_interval(message_id(s, target_.autopilot), interval_us(s),
                                                  system_id_, target_.compid,
                                                  stream.status.attempts));
      ++stream.status.attempts;
      stream.next_send = now + kCommandRetryPeriod;
      return;
    } else {
      in_flight_.reset();
      give_up(s, now, notes);
    }
  }
  for (const VehicleStream s : kVehicleStreams) {
    Stream& stream = at(s);
    if (stream.status.state != StreamState::asking || stream.status.attempts != 0) continue;
    stream.status.asked = true;
    out.emplace_back(build_set_message_interval(message_id(s, target_.autopilot), interval_us(s),
                                                system_id_, target_.compid, 0));
    stream.status.attempts = 1;
    stream.next_send = now + kCommandRetryPeriod;
    in_flight_ = s;
    notes.push_back("asking for " + std::string(mavlink_name(s, target_.autopilot)) + " at " +
                    rate_text(s) + " (SET_MESSAGE_INTERVAL " +
                    std::to_string(message_id(s, target_.autopilot)) + ", " +
                    std::to_string(interval_us(s)) + " us)");
    return;
  }
}

}  // namespace mocaplink::core

// Sender (sender.hpp): decimation, per-profile message emission, clock-driven messages.
#include "mocaplink/core/sender.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mocaplink::core {
namespace {

Duration period_of(double rate_hz) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / rate_hz));
}

bool valid_rate(double rate_hz) {
  return std::isfinite(rate_hz) && rate_hz > 0.0 && rate_hz <= kMaxSenderRateHz;
}

std::uint32_t ms_since(HostTime start, HostTime t) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t - start).count();
  // time_boot_ms wraps after 49.7 days like an autopilot's boot clock.
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(ms < 0 ? 0 : ms) & 0xFFFF'FFFFU);
}

std::int64_t ns_of(HostTime t) {
  return t.time_since_epoch().count();
}

/// Defence in depth against a filter fed absurd input: every state value finite and within
/// kMaxPlausiblePositionM / kMaxPlausibleSpeedMps (also keeps float and int conversions defined).
bool plausible(const BodyEstimate& e) {
  // Finite, all of them at once: x * 0 is (a signed) zero for a finite x and NaN for an infinite
  // or NaN one, so the sum is zero exactly when every value is finite; one vectorised sum where
  // allFinite() tested each of the 85 values in turn (a sixth of the sender's work per pose).
  const auto finite = [](const auto& m) { return (m.array() * 0.0).sum() == 0.0; };
  return finite(e.p_ned_m) && e.p_ned_m.cwiseAbs().maxCoeff() <= kMaxPlausiblePositionM &&
         finite(e.v_ned_mps) && e.v_ned_mps.cwiseAbs().maxCoeff() <= kMaxPlausibleSpeedMps &&
         finite(e.q_ned_frd.coeffs()) && finite(e.w_frd_radps) && finite(e.pose_covariance) &&
         finite(e.velocity_covariance);
}

/// Next time of a periodic message: phase-stable (advance by whole periods), restarting after a
/// gap of more than one period (a stalled caller gets one message, not a burst). The first call
/// sends at once; the second comes `phase` (in [0, period)) later than one period after it, and
/// every later one keeps that phase, after a gap too (the next is the first in phase at least a
/// period on): vehicles of different phases never fall back into one tick.
bool periodic_due(std::optional<HostTime>& next, HostTime now, Duration period, Duration phase) {
  if (!next) {
    next = now + period + phase;
    return true;
  }
  if (now < *next) return false;
  *next += period;
  if (*next <= now) *next += period * ((now + period - *next + period - Duration{1}) / period);
  return true;
}

/// Where in the period a vehicle's clock-driven messages fall (Sender::on_tick): slot i at the
/// fractional part of i times the golden ratio, so that any number of vehicles spread evenly over
/// the period however the daemon's tick divides it; slot 0 at 0.
Duration housekeeping_phase(std::size_t slot, Duration period) {
  constexpr double kGoldenFraction = 0.6180339887498949;
  const double f = std::fmod(static_cast<double>(slot) * kGoldenFraction, 1.0);
  return std::chrono::duration_cast<Duration>(period * f);
}

}  // namespace

std::string max_rate_text() {
  char text[32];
  std::snprintf(text, sizeof text, "%g", kMaxSenderRateHz);
  return text;
}

Sender::Sender(const SenderConfig& config)
    : config_(config),
      period_(period_of(valid_rate(config.rate_hz) ? config.rate_hz : 1.0)),
      phase_(housekeeping_phase(config.vehicle, kHeartbeatPeriod)),
      sequence_(config.system_id, config.component_id) {
  if (!valid_rate(config.rate_hz) || config.component_id == 0 || config.system_id == 0) {
    std::fprintf(stderr, "mocaplink::core::Sender: invalid SenderConfig (rate %g, ids %u/%u)\n",
                 config.rate_hz, config.system_id, config.component_id);
    std::abort();
  }
  if (config.signing_key) {
    signer_.emplace(mavlink::SigningKey(*config.signing_key), config.signing_link_id);
  }
}

bool Sender::set_rate_hz(double rate_hz) {
  if (!valid_rate(rate_hz)) return false;
  config_.rate_hz = rate_hz;
  period_ = period_of(rate_hz);
  // The new spacing counts from the last send: the next frame at least one new period after it
  // sends (at once when that is already past), so the change shows on the next frame.
  if (last_due_capture_) {
    next_due_ = *last_due_capture_ + period_;
  } else {
    next_due_.reset();
  }
  return true;
}

bool Sender::due(SourceTime capture) {
  const auto last = frame_interval_.last();
  const bool backwards = last && capture < *last;
  frame_interval_.observe(capture);
  if (!next_due_ || backwards) {
    // First frame, or the source clock went backwards (restart): start the schedule here.
    next_due_ = capture + period_;
    last_due_capture_ = capture;
    return true;
  }
  // A frame claims the slot nearest to it: up to half a source frame interval early (never more
  // than half our own period), so timestamp rounding and jitter do not push a send one frame late.
  const Duration tolerance =
      std::min(frame_interval_.value().value_or(Duration::zero()), period_) / 2;
  if (capture < *next_due_ - tolerance) return false;
  // Advance by whole periods to the first slot after this frame: slots already past (frames the
  // source dropped, a gap, a mocap rate below rate_hz) are skipped without a burst and without
  // shifting the phase. A frame that claimed its slot late never skips the next one because of
  // the tolerance alone (with jitter, that would lose sends).
  *next_due_ += period_;
  if (*next_due_ <= capture) *next_due_ += period_ * ((capture - *next_due_) / period_ + 1);
  last_due_capture_ = capture;
  return true;
}

void Sender::on_estimate(const BodyEstimate& estimate, const SendContext& context,
                         std::vector<OutgoingMessage>& out) {
  if (estimate.state == TrackingState::unseen) return;  // nothing known yet: nothing to say
  if (!due(estimate.capture_time)) return;
  if (paused_) return;
  if (!plausible(estimate)) {
    ++counters_.implausible;
    return;
  }
  const bool pose_valid = estimate.pose_valid();
  bool any = false;
  for (const MessageDescriptor& row : kMessages) {
    const MessageKind kind = row.kind;
    if (!config_.messages.contains(kind)) continue;
    if (!row.is_gps && !pose_valid) continue;  // never a stale pose (§12 "Common")
    if (row.is_gps && context.origin == nullptr) continue;
    emit_kind(kind, estimate, context, out);
    any = true;
  }
  if (any) {
    last_pose_sent_ = context.now;
    ++counters_.poses;
    pose_sends_.add(context.now);
  } else if (!pose_valid) {
    ++counters_.due_without_pose;
  }
}

void Sender::emit_kind(MessageKind kind, const BodyEstimate& estimate, const SendContext& context,
                       std::vector<OutgoingMessage>& out) {
  const GpsContext gps{context.origin, context.gps, context.gps_time};
  const MessageInputs inputs{host_time_usec(context.capture),
                             ms_since(context.start, context.capture), &gps};
  ++counters_.sent[static_cast<std::size_t>(kind)];
  emit(describe(kind).build(estimate, inputs), context.now, context.signing_now_10us, out);
}

void Sender::on_tick(HostTime now, std::uint64_t signing_now_10us, const GeodeticPosition* origin,
                     bool timesync_request, std::vector<OutgoingMessage>& out) {
  if (periodic_due(next_heartbeat_, now, kHeartbeatPeriod, phase_)) {
    ++counters_.heartbeats;
    emit(build_heartbeat(), now, signing_now_10us, out);
  }
  if (origin != nullptr) {
    if (periodic_due(next_origin_, now, kOriginPeriod, phase_)) {
      ++counters_.origins;
      emit(build_set_gps_global_origin(*origin, config_.system_id, host_time_usec(now)), now,
           signing_now_10us, out);
      // Every third unanswered SET_GPS_GLOBAL_ORIGIN, ask for GPS_GLOBAL_ORIGIN explicitly
      // (§3.9: some firmware does not answer the SET itself).
      if (counters_.origins % 3 == 0) {
        ++counters_.origin_requests;
        emit(build_request_gps_global_origin(config_.system_id, 1), now, signing_now_10us, out);
      }
    }
  } else {
    next_origin_.reset();
  }
  if (timesync_request && periodic_due(next_timesync_, now, kTimesyncRequestPeriod, phase_)) {
    ++counters_.timesync_requests;
    emit(build_timesync_request(ns_of(now), config_.system_id, 1), now, signing_now_10us, out);
  }
}

void Sender::send(const mavlink::Message& message, HostTime now, std::uint64_t signing_now_10us,
                  std::vector<OutgoingMessage>& out) {
  if (std::holds_alternative<mavlink::Timesync>(message)) ++counters_.timesync_replies;
  if (const auto* command = std::get_if<mavlink::CommandLong>(&message)) {
    if (command->command == 511) ++counters_.interval_requests;  // MAV_CMD_SET_MESSAGE_INTERVAL
  }
  if (std::holds_alternative<mavlink::RequestDataStream>(message)) ++counters_.data_stream_requests;
  emit(message, now, signing_now_10us, out);
}

void Sender::emit(const mavlink::Message& message, HostTime now, std::uint64_t signing_now_10us,
                  std::vector<OutgoingMessage>& out) {
  OutgoingMessage& o = out.emplace_back();
  o.vehicle = config_.vehicle;
  o.time = now;
  o.message = message;
  const mavlink::FrameHeader header = sequence_.next();
  if (signer_) {
    const mavlink::SignParams sign = signer_->next(signing_now_10us);
    o.frame = mavlink::encode(message, header, &sign);
  } else {
    o.frame = mavlink::encode(message, header);
  }
  ++counters_.frames;
  counters_.bytes += o.frame.size();
}

SenderSnapshot Sender::snapshot(HostTime now) const {
  SenderSnapshot s;
  s.system_id = config_.system_id;
  s.component_id = config_.component_id;
  s.messages = config_.messages;
  s.rate_hz = config_.rate_hz;
  s.paused = paused_;
  s.signing = signer_.has_value();
  s.last_pose_sent = last_pose_sent_;
  s.send_rate_hz = pose_sends_.rate_hz(now);
  s.counters = counters_;
  return s;
}

}  // namespace mocaplink::core

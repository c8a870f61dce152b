// VehicleSetup (vehicle_setup.hpp): identifies the autopilot, reads the profile's parameters,
// evaluates them (setup_rules.hpp), writes fixes on request and keeps STATUSTEXT and estimator
// health.
#include "mocaplink/core/vehicle_setup.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "mocaplink/core/estimate_sources.hpp"
#include "mocaplink/mavlink/enums.hpp"

namespace mocaplink::core {
namespace {

constexpr std::uint16_t kRequestMessage = 512;  // MAV_CMD_REQUEST_MESSAGE
constexpr std::uint16_t kRebootShutdown = 246;  // MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN
// MAV_PROTOCOL_CAPABILITY_*: PX4 1.14 sets PARAM_FLOAT and PARAM_ENCODE_BYTEWISE, ArduPilot only
// PARAM_FLOAT (the deprecated name of "C cast"), so BYTEWISE wins and FLOAT alone means a cast.
constexpr std::uint64_t kCapParamFloat = 2;
constexpr std::uint64_t kCapBytewise = 16;
constexpr std::uint64_t kCapCCast = 131072;
/// PX4 translates capture times with TIMESYNC only when the round trip is below this (§3.10).
constexpr double kPx4TimesyncMaxRttMs = 10.0;
/// A STATUSTEXT repeated within this is logged once.
constexpr Duration kStatusTextRepeat = std::chrono::seconds(30);

// MAV_PARAM_TYPE
constexpr std::uint8_t kUint8 = 1, kInt8 = 2, kUint16 = 3, kInt16 = 4, kUint32 = 5, kInt32 = 6,
                       kReal32 = 9, kReal64 = 10;

std::string param_name(const std::array<char, 16>& id) {
  const auto end = std::find(id.begin(), id.end(), '\0');
  return {id.begin(), end};
}

std::array<char, 16> param_id(std::string_view name) {
  std::array<char, 16> id{};
  std::copy_n(name.begin(), std::min(name.size(), id.size()), id.begin());
  return id;
}

bool same_value(double a, double b, std::uint8_t type) {
  if (type == kReal32 || type == kReal64) {
    return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b));
  }
  return a == b;
}

std::string printable(const std::array<char, 50>& raw) {
  std::string text;
  for (const char c : raw) {
    if (c == '\0') break;
    text.push_back(c >= 0x20 && c < 0x7F ? c : '?');
  }
  return text;
}

struct FlagWord {
  std::uint32_t bit;
  std::string_view good;
  std::string_view missing;  ///< "" when its absence is no problem
};

// EKF_STATUS_FLAGS (ardupilotmega.xml) and ESTIMATOR_STATUS_FLAGS (common.xml) share bits 1..512.
constexpr std::array<FlagWord, 7> kStatusFlags{{
    {1, "attitude", "no attitude"},
    {2, "horizontal velocity", "no horizontal velocity"},
    {4, "vertical velocity", "no vertical velocity"},
    {8, "horizontal position", "no horizontal position"},
    {16, "absolute horizontal position", "no absolute horizontal position (origin not set?)"},
    {32, "absolute height", "no absolute height"},
    {64, "height above ground", ""},
}};

EstimatorHealth describe(std::string_view source, std::uint16_t flags,
                         std::span<const FlagWord> bad) {
  EstimatorHealth h;
  h.source = source;
  h.flags = flags;
  for (const FlagWord& f : kStatusFlags) {
    if ((flags & f.bit) != 0) {
      h.good.push_back(f.good);
    } else if (!f.missing.empty()) {
      h.problems.push_back(f.missing);
    }
  }
  for (const FlagWord& f : bad) {
    if ((flags & f.bit) != 0) h.problems.push_back(f.good);
  }
  return h;
}

}  // namespace

std::string_view to_string(SetupState state) {
  switch (state) {
    case SetupState::waiting:
      return "waiting";
    case SetupState::identifying:
      return "identifying";
    case SetupState::reading:
      return "reading";
    case SetupState::ready:
      return "ready";
    case SetupState::blocked:
      return "blocked";
    case SetupState::no_answer:
      return "no answer";
    case SetupState::unsupported:
      return "unsupported";
    case SetupState::unavailable:
      return "unavailable";
  }
  return "waiting";
}

std::string_view unavailable_reason(VehicleLink link) {
  switch (link) {
    case VehicleLink::mavlink:
      return "";
    case VehicleLink::px4_dds:
      return "PX4's parameters do not go over uXRCE-DDS: check this list over a MAVLink link to "
             "the same PX4 (mocaplink vehicle setup, or QGroundControl)";
  }
  return "";
}

std::string_view to_string(ApplyState state) {
  switch (state) {
    case ApplyState::none:
      return "none";
    case ApplyState::pending:
      return "pending";
    case ApplyState::confirmed:
      return "confirmed";
    case ApplyState::failed:
      return "failed";
  }
  return "none";
}

std::string_view severity_name(std::uint8_t severity) {
  static constexpr std::array<std::string_view, 8> kNames{
      "emergency", "alert", "critical", "error", "warning", "notice", "info", "debug"};
  return severity < kNames.size() ? kNames[severity] : "unknown";
}

EstimatorHealth describe_ekf_status(std::uint16_t flags) {
  static constexpr std::array<FlagWord, 3> kBad{{
      {128, "constant position mode (no position source)", ""},
      {1024, "not initialised", ""},
      {32768, "GPS glitch", ""},
  }};
  return describe("EKF_STATUS_REPORT", flags, kBad);
}

EstimatorHealth describe_estimator_status(std::uint16_t flags) {
  static constexpr std::array<FlagWord, 3> kBad{{
      {128, "constant position mode (no position source)", ""},
      {1024, "GPS glitch", ""},
      {2048, "accelerometer error", ""},
  }};
  EstimatorHealth h = describe("ESTIMATOR_STATUS", flags, kBad);
  // PX4 1.14 sets ESTIMATOR_ATTITUDE only once its heading is aligned to north, which vision yaw
  // in a local frame (mocaplink's ODOMETRY, MAV_FRAME_LOCAL_FRD) never does: with a horizontal
  // position (8) it flew closed-loop in SITL, the flag clear throughout. Not a problem then.
  if ((flags & 1U) == 0 && (flags & 8U) != 0) {
    std::erase(h.problems, std::string_view("no attitude"));
    h.good.insert(h.good.begin(),
                  "attitude (not flagged: a mocap heading is not aligned to north)");
  }
  return h;
}

VehicleSetup::VehicleSetup(std::uint8_t system_id, std::uint8_t component_id, Profile profile,
                           MessageSet messages, VehicleLink link)
    : system_id_(system_id),
      component_id_(component_id),
      profile_(profile),
      messages_(messages),
      link_(link) {}

void VehicleSetup::restart(HostTime now) {
  version_.reset();
  capabilities_.reset();
  version_attempts_ = 0;
  version_done_ = false;
  reading_.reset();
  writing_.reset();
  params_.clear();
  rules_.clear();
  reboot_for_.clear();
  next_send_ = now;
  state_ = SetupState::identifying;
}

void VehicleSetup::on_reboot(HostTime now) {
  if (state_ != SetupState::waiting) restart(now);
}

void VehicleSetup::set_messages(MessageSet messages) {
  messages_ = messages;
  if (version_done_) choose_rules();
}

void VehicleSetup::choose_rules() {
  rules_ = rules_for(family_, version_, setup_input(family_, messages_));
  std::vector<Param> params;
  const auto add = [&](std::string_view name) {
    const auto same = [&](const Param& p) { return p.name == name; };
    if (std::any_of(params.begin(), params.end(), same)) return;
    const auto old = std::find_if(params_.begin(), params_.end(), same);
    if (old != params_.end()) {
      params.push_back(*old);
    } else {
      Param fresh;
      fresh.name = std::string(name);
      params.push_back(std::move(fresh));
    }
  };
  for (const SetupRule* rule : rules_) add(rule->parameter);
  // Read too, with no line of their own: what the agreement check's sources need
  // (estimate_sources.hpp, the second heading).
  for (const std::string_view name : source_parameters(family_)) add(name);
  params_ = std::move(params);
  reading_.reset();
  writing_.reset();
}

VehicleSetup::Param* VehicleSetup::find(std::string_view name) {
  const auto it =
      std::find_if(params_.begin(), params_.end(), [&](const Param& p) { return p.name == name; });
  return it == params_.end() ? nullptr : &*it;
}

SetupInput VehicleSetup::input() const {
  return setup_input(family_, messages_);
}

std::optional<double> VehicleSetup::parameter(std::string_view name) const {
  const auto it =
      std::find_if(params_.begin(), params_.end(), [&](const Param& p) { return p.name == name; });
  return it == params_.end() ? std::nullopt : it->value;
}

bool VehicleSetup::bytewise() const {
  if (capabilities_) {
    if ((*capabilities_ & kCapBytewise) != 0) return true;
    if ((*capabilities_ & (kCapCCast | kCapParamFloat)) != 0) return false;
  }
  return family_ == AutopilotFamily::px4;
}

std::optional<double> VehicleSetup::decode(const mavlink::ParamValue& value) const {
  const float f = value.param_value;
  const std::uint8_t type = value.param_type;
  if (type == kReal32 || type == kReal64 || !bytewise()) {
    if (!std::isfinite(f)) return std::nullopt;
    if (type < kUint8 || type > kReal64) return std::nullopt;
    return static_cast<double>(f);
  }
  const auto bits = std::bit_cast<std::uint32_t>(f);
  switch (type) {
    case kUint8:
      return static_cast<double>(bits & 0xFFu);
    case kInt8:
      return static_cast<double>(static_cast<std::int8_t>(bits & 0xFFu));
    case kUint16:
      return static_cast<double>(bits & 0xFFFFu);
    case kInt16:
      return static_cast<double>(static_cast<std::int16_t>(bits & 0xFFFFu));
    case kUint32:
      return static_cast<double>(bits);
    case kInt32:
      return static_cast<double>(std::bit_cast<std::int32_t>(bits));
    default:
      return std::nullopt;  // 64-bit integers do not fit a bytewise float
  }
}

float VehicleSetup::encode(double value, std::uint8_t type) const {
  if (type == kReal32 || type == kReal64 || !bytewise()) return static_cast<float>(value);
  std::uint32_t bits = 0;
  switch (type) {
    case kUint8:
    case kUint16:
    case kUint32:
      bits = static_cast<std::uint32_t>(value);
      break;
    default:
      bits = std::bit_cast<std::uint32_t>(static_cast<std::int32_t>(value));
      break;
  }
  if (type == kInt8) bits &= 0xFFu;
  if (type == kInt16) bits &= 0xFFFFu;
  return std::bit_cast<float>(bits);
}

void VehicleSetup::on_message(const ReceivedMessage& message, HostTime now,
                              std::vector<std::string>& notes) {
  if (message.sysid != system_id_) return;
  if (const auto* hb = std::get_if<mavlink::Heartbeat>(&message.message)) {
    // Armed at once, not at the next tick: apply() and reboot() must never act on a vehicle that
    // has just armed (a GCS (type 6) or a non-autopilot component (autopilot 8) does not count).
    if (hb->type != 6 && hb->autopilot != 8) {
      target_.armed = (hb->base_mode & kMavModeFlagSafetyArmed) != 0;
    }
  } else if (const auto* v = std::get_if<mavlink::AutopilotVersion>(&message.message)) {
    if (version_done_ && version_) return;
    version_ = decode_flight_sw_version(v->flight_sw_version);
    capabilities_ = v->capabilities;
    if (state_ == SetupState::identifying) {
      version_done_ = true;
      choose_rules();
      notes.push_back("autopilot " + std::string(to_string(family_)) + " " +
                      (version_ ? to_string(*version_) : std::string("(version not given)")) +
                      ": reading " + std::to_string(params_.size()) + " parameters");
    }
  } else if (const auto* ack = std::get_if<mavlink::CommandAck>(&message.message)) {
    // The answer to our reboot, addressed to us (0: a MAVLink 1 ACK without targets). PX4 SITL,
    // for one, refuses it (DENIED: a posix build has no reset): said, not taken as done.
    if (!reboot_asked_ || ack->command != kRebootShutdown) return;
    if (ack->target_system != 0 && ack->target_system != system_id_) return;
    if (ack->target_component != 0 && ack->target_component != component_id_) return;
    const auto result_code = static_cast<mavlink::MavResult>(ack->result);
    if (result_code == mavlink::MavResult::in_progress) return;  // the final answer follows
    reboot_asked_ = false;
    if (result_code == mavlink::MavResult::accepted) {
      notes.emplace_back("the vehicle accepted the reboot");
      return;
    }
    const std::string_view result = mavlink::to_string(result_code);
    last_refusal_ =
        "the vehicle refused the reboot (" +
        (result.empty() ? "MAV_RESULT " + std::to_string(ack->result) : std::string(result)) +
        "): restart it by hand for the changes that wait for a reboot";
    notes.push_back(last_refusal_);
  } else if (const auto* p = std::get_if<mavlink::ParamValue>(&message.message)) {
    on_param_value(*p, now, notes);
  } else if (const auto* t = std::get_if<mavlink::Statustext>(&message.message)) {
    on_statustext(*t, now, notes);
  } else if (const auto* e = std::get_if<mavlink::EkfStatusReport>(&message.message)) {
    estimator_ = describe_ekf_status(e->flags);
    estimator_->time = now;
  } else if (const auto* s = std::get_if<mavlink::EstimatorStatus>(&message.message)) {
    estimator_ = describe_estimator_status(s->flags);
    estimator_->time = now;
  }
}

void VehicleSetup::on_param_value(const mavlink::ParamValue& value, HostTime now,
                                  std::vector<std::string>& notes) {
  const std::string name = param_name(value.param_id);
  Param* p = find(name);
  if (p == nullptr) return;
  const std::optional<double> v = decode(value);
  if (!v) {
    ++counters_.malformed;
    return;
  }
  ++counters_.param_values;
  const std::size_t index = static_cast<std::size_t>(p - params_.data());
  const std::optional<double> before = p->value;
  p->value = v;
  p->type = value.param_type;
  p->gave_up = false;
  if (reading_ == index) {
    reading_.reset();
    next_send_ = now + kParamGap;
  }
  // The answer to our write, once it was sent (a value announced before it is a value).
  if (p->writing && p->write_attempts > 0) {
    const double wanted = *p->writing;
    p->writing.reset();
    if (writing_ == index) {
      writing_.reset();
      next_send_ = now + kParamGap;
    }
    if (same_value(*v, wanted, value.param_type)) {
      p->apply = ApplyState::confirmed;
      p->apply_note = "set to " + format_value(*v);
      const auto rule = std::find_if(rules_.begin(), rules_.end(),
                                     [&](const SetupRule* r) { return r->parameter == name; });
      std::string note = name + " set to " + format_value(*v) + " (confirmed by the vehicle)";
      if (rule != rules_.end() && (*rule)->reboot) {
        reboot_for_.push_back(name);
        note += "; takes effect after a reboot";
      }
      notes.push_back(note);
    } else {
      p->apply = ApplyState::failed;
      p->apply_note = "the vehicle kept " + format_value(*v);
      notes.push_back(name + ": wrote " + format_value(wanted) + ", the vehicle kept " +
                      format_value(*v));
    }
  } else if (before && !same_value(*before, *v, value.param_type)) {
    notes.push_back(name + " changed from " + format_value(*before) + " to " + format_value(*v) +
                    " (by the vehicle or a ground station)");
  }
}

void VehicleSetup::on_statustext(const mavlink::Statustext& text, HostTime now,
                                 std::vector<std::string>& notes) {
  StatusText s{now, text.severity, printable(text.text)};
  if (s.text.empty()) return;
  // Warnings and worse go to the log, once per kStatusTextRepeat for the same text.
  const bool repeated =
      std::any_of(statustext_.begin(), statustext_.end(), [&](const StatusText& old) {
        return old.text == s.text && now - old.time < kStatusTextRepeat;
      });
  if (s.severity <= 4 && !repeated) {
    notes.push_back("vehicle says (" + std::string(severity_name(s.severity)) + "): " + s.text);
  }
  statustext_.push_back(std::move(s));
  while (statustext_.size() > kStatusTextKeep) statustext_.pop_front();
}

void VehicleSetup::on_tick(HostTime now, const SetupTarget& target, const DelayInputs& delay,
                           std::vector<mavlink::Message>& out, std::vector<std::string>& notes) {
  delay_ = delay;
  const bool was_alive = target_.alive;
  target_ = target;
  if (!target.alive) return;
  const AutopilotFamily family = autopilot_family(target.autopilot);
  if (!was_alive || family != family_) {
    family_ = family;
    restart(now);
  }
  if (family_ != AutopilotFamily::px4 && family_ != AutopilotFamily::ardupilot) {
    state_ = SetupState::unsupported;
    update_state(notes);
    return;
  }
  if (link_ != VehicleLink::mavlink) {
    // Nothing can be asked: the newest firmware's rules, every item unread.
    if (!version_done_) {
      version_done_ = true;
      choose_rules();
    }
    state_ = SetupState::unavailable;
    update_state(notes);
    return;
  }
  if (!version_done_) {
    if (next_send_ && now < *next_send_) return;
    if (version_attempts_ >= kVersionAttempts) {
      version_done_ = true;
      choose_rules();
      notes.push_back("autopilot " + std::string(to_string(family_)) +
                      " did not answer for AUTOPILOT_VERSION (" + std::to_string(kVersionAttempts) +
                      " tries): the newest firmware's parameter names are assumed");
    } else {
      mavlink::CommandLong m;
      m.command = kRequestMessage;
      m.param1 = static_cast<float>(mavlink::AutopilotVersion::kId);
      m.target_system = system_id_;
      m.target_component = target.compid;
      m.confirmation = version_attempts_;
      out.emplace_back(m);
      ++version_attempts_;
      ++counters_.version_requests;
      next_send_ = now + kSetupRetryPeriod;
      return;
    }
  }
  if (target.armed) {
    for (Param& p : params_) {
      if (!p.writing) continue;
      p.writing.reset();
      p.apply = ApplyState::failed;
      p.apply_note = "stopped: the vehicle armed";
      notes.push_back(p.name + ": not written, the vehicle armed");
    }
    writing_.reset();
  }
  tick_writes(now, out, notes);
  if (!writing_) tick_reads(now, out);
  update_state(notes);
}

void VehicleSetup::tick_reads(HostTime now, std::vector<mavlink::Message>& out) {
  if (next_send_ && now < *next_send_) return;
  if (reading_) {
    Param& p = params_[*reading_];
    reading_.reset();
    if (p.attempts >= kParamAttempts) p.gave_up = true;
  }
  for (std::size_t i = 0; i < params_.size(); ++i) {
    Param& p = params_[i];
    if (p.value || p.gave_up) continue;
    if (p.attempts >= kParamAttempts) {
      p.gave_up = true;
      continue;
    }
    mavlink::ParamRequestRead m;
    m.target_system = system_id_;
    m.target_component = target_.compid;
    m.param_id = param_id(p.name);
    m.param_index = -1;
    out.emplace_back(m);
    ++p.attempts;
    ++counters_.param_requests;
    reading_ = i;
    next_send_ = now + kSetupRetryPeriod;
    return;
  }
}

void VehicleSetup::tick_writes(HostTime now, std::vector<mavlink::Message>& out,
                               std::vector<std::string>& notes) {
  if (next_send_ && now < *next_send_) return;
  if (!writing_) {
    const auto it = std::find_if(params_.begin(), params_.end(),
                                 [](const Param& p) { return p.writing.has_value(); });
    if (it == params_.end()) return;
    writing_ = static_cast<std::size_t>(it - params_.begin());
  }
  Param& p = params_[*writing_];
  if (p.write_attempts >= kParamAttempts) {
    p.writing.reset();
    p.apply = ApplyState::failed;
    p.apply_note = "no answer after " + std::to_string(kParamAttempts) + " tries";
    notes.push_back(p.name + ": the vehicle never confirmed the write (" +
                    std::to_string(kParamAttempts) + " tries)");
    writing_.reset();
    next_send_ = now + kParamGap;
    return;
  }
  mavlink::ParamSet m;
  m.target_system = system_id_;
  m.target_component = target_.compid;
  m.param_id = param_id(p.name);
  m.param_type = p.type;
  m.param_value = encode(*p.writing, p.type);
  out.emplace_back(m);
  ++p.write_attempts;
  ++counters_.param_sets;
  next_send_ = now + kSetupRetryPeriod;
}

void VehicleSetup::update_state(std::vector<std::string>& notes) {
  if (state_ != SetupState::unsupported && state_ != SetupState::unavailable) {
    const bool pending = std::any_of(params_.begin(), params_.end(),
                                     [](const Param& p) { return !p.value && !p.gave_up; });
    const bool any_value =
        std::any_of(params_.begin(), params_.end(), [](const Param& p) { return p.value; });
    if (!version_done_) {
      state_ = SetupState::identifying;
    } else if (pending) {
      state_ = SetupState::reading;
    } else if (!any_value && !params_.empty()) {
      state_ = SetupState::no_answer;
    } else {
      const std::vector<SetupLine> list = lines();
      const bool blocks = std::any_of(list.begin(), list.end(), [](const SetupLine& l) {
        return l.item.severity == SetupSeverity::blocks &&
               (l.item.status == SetupStatus::wrong || l.item.status == SetupStatus::missing);
      });
      state_ = blocks ? SetupState::blocked : SetupState::ready;
    }
  }
  if (state_ == announced_) return;
  announced_ = state_;
  if (state_ == SetupState::identifying || state_ == SetupState::reading) return;
  std::string text = "set-up " + std::string(to_string(state_));
  if (state_ == SetupState::unsupported) {
    text += ": no set-up rules for this autopilot (only PX4 and ArduPilot)";
  } else if (state_ == SetupState::unavailable) {
    text += ": " + std::string(unavailable_reason(link_));
  } else if (state_ == SetupState::no_answer) {
    text += ": the vehicle answered none of " + std::to_string(params_.size()) +
            " parameter reads (does this link carry the parameter protocol?)";
  } else {
    std::string wrong;
    for (const SetupLine& l : lines()) {
      if (l.item.status != SetupStatus::wrong && l.item.status != SetupStatus::missing) continue;
      if (l.item.severity == SetupSeverity::advice) continue;
      wrong += (wrong.empty() ? "" : "; ") + l.item.parameter + " " +
               (l.item.current ? "is " + format_value(*l.item.current) : std::string("missing")) +
               ", needs " + l.item.needed + " (" + std::string(to_string(l.item.severity)) + ")";
    }
    if (!wrong.empty()) text += ": " + wrong;
  }
  notes.push_back(text);
}

const SetupRule* VehicleSetup::delay_rule() const {
  const auto it = std::find_if(rules_.begin(), rules_.end(), [](const SetupRule* r) {
    return r->fix.kind == SetupFix::Kind::measured_delay;
  });
  return it == rules_.end() ? nullptr : *it;
}

std::optional<double> VehicleSetup::recommended_delay() const {
  if (!delay_.capture_age_ms) return std::nullopt;
  const double measured =
      *delay_.capture_age_ms + (delay_.link_rtt_ms ? *delay_.link_rtt_ms / 2 : 0);
  // PX4 places a pose at its capture time once its TIMESYNC filter converges, which it does only
  // over a link with a round trip below 10 ms (§3.10, §4.1): EKF2_EV_DELAY then covers nothing.
  if (family_ == AutopilotFamily::px4 && setup_input(family_, messages_) == SetupInput::vision &&
      delay_.vehicle_timesync && delay_.link_rtt_ms && *delay_.link_rtt_ms < kPx4TimesyncMaxRttMs) {
    return 0.0;
  }
  // Over uXRCE-DDS PX4's client converts timestamp_sample from the Agent host's clock, clamped to
  // "not in the future" (§4 of ros2-dds.md): the capture time is kept however long delivery took.
  if (family_ == AutopilotFamily::px4 && delay_.dds_time_sync) return 0.0;
  return measured;
}

std::vector<SetupLine> VehicleSetup::lines() const {
  std::vector<SetupLine> out;
  if (auto item = profile_item(profile_, family_, setup_input(family_, messages_))) {
    out.push_back({std::move(*item), ApplyState::none, {}});
  }
  const std::optional<double> delay = recommended_delay();
  for (const SetupRule* rule : rules_) {
    const auto p = std::find_if(params_.begin(), params_.end(),
                                [&](const Param& q) { return q.name == rule->parameter; });
    if (p == params_.end()) continue;
    SetupLine line{evaluate_rule(*rule, p->value, p->gave_up, delay), p->apply, p->apply_note};
    if (line.item.status == SetupStatus::missing) {
      line.item.why = "the vehicle did not answer for this parameter (" +
                      std::to_string(kParamAttempts) + " tries): not in this firmware? " +
                      line.item.why;
    }
    out.push_back(std::move(line));
  }
  return out;
}

SetupRequestResult VehicleSetup::apply(std::span<const std::string> parameters, HostTime now) {
  const auto refuse = [&](std::string why) {
    last_refusal_ = why;
    return SetupRequestResult{false, std::move(why)};
  };
  if (link_ != VehicleLink::mavlink) return refuse(std::string(unavailable_reason(link_)));
  if (target_.armed) return refuse("the vehicle is armed: nothing is written to an armed vehicle");
  if (state_ != SetupState::ready && state_ != SetupState::blocked) {
    return refuse("the list is not complete (set-up " + std::string(to_string(state_)) +
                  "): nothing was written");
  }
  if (std::any_of(params_.begin(), params_.end(),
                  [](const Param& p) { return p.writing.has_value(); })) {
    return refuse("a previous apply is still being written");
  }
  if (parameters.empty()) {
    return refuse(
        "name the parameters to change (the wrong ones of the list): nothing was written");
  }
  const std::vector<SetupLine> list = lines();
  std::vector<std::pair<std::string, double>> fixes;
  for (const std::string& name : parameters) {
    const auto line = std::find_if(list.begin(), list.end(), [&](const SetupLine& l) {
      return l.item.parameter == name && l.item.status == SetupStatus::wrong && l.item.fix;
    });
    if (line == list.end() || find(name) == nullptr) {
      return refuse(name +
                    " is not a wrong parameter of the list as it stands: nothing was written");
    }
    if (std::none_of(fixes.begin(), fixes.end(), [&](const auto& f) { return f.first == name; })) {
      fixes.emplace_back(name, *line->item.fix);
    }
  }
  std::string message = "writing";
  for (const auto& [name, value] : fixes) {
    Param& p = *find(name);
    p.writing = value;
    p.write_attempts = 0;
    p.apply = ApplyState::pending;
    p.apply_note.clear();
    message += " " + name + "=" + format_value(value);
  }
  if (!next_send_ || *next_send_ > now + kParamGap) next_send_ = now;
  last_refusal_.clear();
  return {true, message};
}

SetupRequestResult VehicleSetup::reboot(HostTime now, std::vector<mavlink::Message>& out) {
  (void)now;
  if (link_ != VehicleLink::mavlink) {
    last_refusal_ = "PX4 is not rebooted over uXRCE-DDS: restart it over a MAVLink link or by hand";
    return {false, last_refusal_};
  }
  if (!target_.alive) {
    last_refusal_ = "no heartbeat from the vehicle";
    return {false, last_refusal_};
  }
  if (target_.armed) {
    last_refusal_ = "the vehicle is armed: it is not rebooted";
    return {false, last_refusal_};
  }
  mavlink::CommandLong m;
  m.command = kRebootShutdown;
  m.param1 = 1;  // reboot the autopilot
  m.target_system = system_id_;
  m.target_component = target_.compid;
  out.emplace_back(m);
  last_refusal_.clear();
  reboot_asked_ = true;
  return {true, "reboot asked of the autopilot"};
}

VehicleSetupSnapshot VehicleSetup::snapshot() const {
  VehicleSetupSnapshot s;
  s.state = state_;
  s.autopilot = family_;
  s.version = version_;
  s.identified = version_done_;
  s.input = setup_input(family_, messages_);
  s.lines = lines();
  s.statustext.assign(statustext_.begin(), statustext_.end());
  s.estimator = estimator_;
  s.armed = target_.armed;
  s.reboot_for = reboot_for_;
  s.counters = counters_;
  s.last_refusal = last_refusal_;
  if (const SetupRule* rule = delay_rule()) {
    s.delay.parameter = std::string(rule->parameter);
    s.delay.recommended_ms = recommended_delay();
    if (s.delay.recommended_ms) {
      s.delay.recommended_ms =
          std::clamp(std::round(*s.delay.recommended_ms), rule->min_value, rule->max_value);
    }
    const auto p = std::find_if(params_.begin(), params_.end(),
                                [&](const Param& q) { return q.name == rule->parameter; });
    if (p != params_.end()) s.delay.current_ms = p->value;
    if (delay_.capture_age_ms) {
      s.delay.measured_ms =
          *delay_.capture_age_ms + (delay_.link_rtt_ms ? *delay_.link_rtt_ms / 2 : 0);
      const bool dds = link_ == VehicleLink::px4_dds;
      s.delay.basis =
          "capture to mocaplink (median) " + format_value(*delay_.capture_age_ms) + " ms" +
          (delay_.link_rtt_ms
               ? " + half the link round trip " + format_value(*delay_.link_rtt_ms / 2) + " ms"
           : dds ? std::string()
                 : std::string(" (link round trip not measured yet)"));
      if (dds && delay_.dds_time_sync && s.delay.recommended_ms == 0.0) {
        s.delay.basis +=
            "; PX4 translates the capture time with its uXRCE-DDS time sync, so 0 is right while "
            "mocaplink runs on the Agent's host (or both hosts keep NTP time)";
      } else if (dds) {
        s.delay.basis +=
            "; PX4 stamps these poses on arrival (its uXRCE-DDS time sync is not within 5 ms of "
            "this host's clock), so the delay is the whole of it, and DDS delivery adds a few ms";
      } else if (family_ == AutopilotFamily::px4 && s.delay.recommended_ms == 0.0) {
        s.delay.basis += "; PX4 translates the capture time with TIMESYNC, so 0 is right";
      }
    }
  }
  return s;
}

}  // namespace mocaplink::core

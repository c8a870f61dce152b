#include "mocaplink/wire/vrpn_client.hpp"

#include <algorithm>

namespace mocaplink::wire::vrpn {

namespace {

/// Stores `name` under `id` unless the table is full; true if stored.
bool remember(std::unordered_map<std::int32_t, std::string>& table, std::int32_t id,
              std::string name) {
  auto it = table.find(id);
  if (it != table.end()) {
    it->second = std::move(name);
    return true;
  }
  if (table.size() >= kMaxIds) return false;
  table.emplace(id, std::move(name));
  return true;
}

}  // namespace

Result<MessageOutcome> ClientTables::apply(const Header& header,
                                           std::span<const std::byte> payload) {
  MessageOutcome out;
  if (header.type == kSenderDescription || header.type == kTypeDescription) {
    auto name = parse_description(payload);
    if (!name) return name.error();
    const bool sender = header.type == kSenderDescription;
    const bool first = sender && std::find(sender_order_.begin(), sender_order_.end(),
                                           name.value()) == sender_order_.end();
    if (!remember(sender ? senders_ : types_, header.sender, name.value())) {
      out.over_limit = true;
      return out;
    }
    out.described = true;
    if (first && sender_order_.size() < kMaxIds) {
      sender_order_.push_back(name.value());
      out.new_sender = std::move(name).value();
    }
    return out;
  }
  if (header.type < 0) return out;  // UDP / log descriptions and other system messages
  const auto type = types_.find(header.type);
  const auto sender = senders_.find(header.sender);
  if (type == types_.end() || sender == senders_.end()) {
    out.unknown_id = true;
    return out;
  }
  if (type->second != kPosQuatType) return out;
  auto pose = parse_pos_quat(payload);
  if (!pose) return pose.error();
  out.report = Report{sender->second, std::move(pose).value(), header.time};
  return out;
}

std::string body_name(const std::string& tracker, std::int32_t sensor) {
  return sensor == 0 ? tracker : tracker + ":" + std::to_string(sensor);
}

std::optional<AssembledFrame> FrameAssembler::on_report(const Report& report,
                                                        core::HostTime arrival) {
  Key key{report.tracker, report.pose.sensor};
  auto it = index_.find(key);
  if (it == index_.end()) {
    if (known_.size() >= config_.max_bodies) {
      ++ignored_bodies_;
      return std::nullopt;
    }
    it = index_.emplace(std::move(key), known_.size()).first;
    known_.push_back(Known{body_name(report.tracker, report.pose.sensor), report.pose.p_m,
                           report.pose.q_world_sensor, arrival});
  }
  const std::size_t k = it->second;
  std::optional<AssembledFrame> closed;
  if (in_round_.contains(k)) closed = close_round();
  Known& body = known_[k];
  const bool same =
      body.p_m == report.pose.p_m && body.q.coeffs() == report.pose.q_world_sensor.coeffs();
  if (!same) body.changed = arrival;
  body.p_m = report.pose.p_m;
  body.q = report.pose.q_world_sensor;
  const bool frozen =
      config_.frozen_after.count() > 0 && arrival - body.changed >= config_.frozen_after;
  if (frozen) ++frozen_samples_;
  if (!round_start_) {
    round_start_ = arrival;
    round_stamp_ = report.time;
  }
  round_.push_back(Pending{k, !frozen});
  in_round_.insert(k);
  round_last_ = arrival;
  settling_ = false;  // judged again at the next drain
  last_report_ = arrival;
  lost_sent_ = false;
  return closed;
}

std::optional<AssembledFrame> FrameAssembler::on_drained() {
  if (round_.empty()) return std::nullopt;
  if (!std::includes(in_round_.begin(), in_round_.end(), previous_round_.begin(),
                     previous_round_.end())) {
    settling_ = true;
    return std::nullopt;
  }
  return close_round();
}

void FrameAssembler::reset() {
  index_.clear();
  known_.clear();
  round_.clear();
  in_round_.clear();
  previous_round_.clear();
  round_start_.reset();
  round_stamp_.reset();
  last_stamp_.reset();
  last_report_.reset();
  settling_ = false;
  lost_sent_ = true;
}

std::optional<AssembledFrame> FrameAssembler::flush() {
  if (round_.empty()) return std::nullopt;
  return close_round();
}

core::SourceTime FrameAssembler::next_capture(core::HostTime host, std::optional<Timeval> stamp) {
  std::optional<core::Duration> step;
  if (stamp && last_stamp_) {
    const auto us = [](const Timeval& t) {
      return static_cast<std::int64_t>(t.sec) * 1'000'000 + static_cast<std::int64_t>(t.usec);
    };
    step = std::chrono::microseconds(us(*stamp) - us(*last_stamp_));
  }
  last_stamp_ = stamp;
  return clock_.next(host, step);
}

AssembledFrame FrameAssembler::close_round() {
  core::MocapFrame frame;
  frame.frame_number = next_frame_++;
  frame.frame_step = 0;
  frame.capture_time = next_capture(*round_start_, round_stamp_);
  for (const Pending& p : round_) {
    core::BodySample s;
    s.name = known_[p.key].name;
    s.tracked = p.tracked;
    s.p_world_m = known_[p.key].p_m;
    s.q_world_body = known_[p.key].q;
    frame.bodies.push_back(std::move(s));
  }
  previous_round_ = std::move(in_round_);
  in_round_.clear();
  round_.clear();
  round_start_.reset();
  round_stamp_.reset();
  settling_ = false;
  lost_sent_ = false;
  return AssembledFrame{std::move(frame), round_last_};
}

std::optional<core::HostTime> FrameAssembler::idle_deadline() const {
  if (lost_sent_ || !last_report_) return std::nullopt;
  const core::HostTime lost = *last_report_ + config_.lost_after;
  if (settling_ && !round_.empty()) return std::min(lost, round_last_ + config_.settle_after);
  return lost;
}

std::optional<AssembledFrame> FrameAssembler::on_idle(core::HostTime now) {
  if (settling_ && !round_.empty() && now >= round_last_ + config_.settle_after) {
    return close_round();  // nothing more of it came: deliver it now, not at the next update
  }
  const auto deadline = idle_deadline();
  if (!deadline || now < *deadline) return std::nullopt;
  std::optional<AssembledFrame> pending = flush();
  if (pending) return pending;  // an incomplete round first; the loss frame next time
  lost_sent_ = true;
  previous_round_.clear();
  core::MocapFrame frame;
  frame.frame_number = next_frame_++;
  frame.frame_step = 0;
  frame.capture_time = next_capture(now, std::nullopt);
  for (const Known& k : known_) {
    core::BodySample s;
    s.name = k.name;
    frame.bodies.push_back(std::move(s));
  }
  return AssembledFrame{std::move(frame), now};
}

}  // namespace mocaplink::wire::vrpn

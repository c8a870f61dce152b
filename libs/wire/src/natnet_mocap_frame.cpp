#include "mocaplink/wire/natnet_mocap_frame.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <utility>

namespace mocaplink::wire::natnet {

namespace {

// Ticks → ns without overflow for any u64 tick count and clock up to 10 GHz.
std::int64_t ticks_to_ns(std::uint64_t ticks, std::uint64_t clock_hz) {
  const std::uint64_t seconds = ticks / clock_hz;
  const std::uint64_t rest = ticks % clock_hz;
  const long double ns = static_cast<long double>(seconds) * 1e9L +
                         static_cast<long double>(rest) * 1e9L / static_cast<long double>(clock_hz);
  if (ns > 9.2e18L) return INT64_MAX;
  return static_cast<std::int64_t>(std::llround(ns));
}

std::uint64_t ns_to_ticks(std::int64_t ns, std::uint64_t clock_hz) {
  if (ns <= 0) return 0;
  const auto u = static_cast<std::uint64_t>(ns);
  return (u / 1'000'000'000u) * clock_hz +
         static_cast<std::uint64_t>(static_cast<long double>(u % 1'000'000'000u) *
                                    static_cast<long double>(clock_hz) / 1e9L);
}

constexpr double kUnitTolerance = 0.01;

// Motive's Y-up axes in z-up coordinates: a rotation of −90° about x.
const Eigen::Quaterniond& z_to_y() {
  static const Eigen::Quaterniond q(
      Eigen::AngleAxisd(-std::numbers::pi / 2.0, Eigen::Vector3d::UnitX()));
  return q;
}

}  // namespace

BodyTable body_table(const ModelDefinitions& defs) {
  BodyTable t;
  std::map<std::string, int> uses;
  for (const auto& rb : defs.rigid_bodies) ++uses[rb.name];
  for (const auto& rb : defs.rigid_bodies) {
    if (uses[rb.name] > 1) {
      t.ambiguous.insert(rb.name);
    } else {
      t.names[rb.id] = rb.name;
    }
  }
  return t;
}

MappedFrame to_mocap_frame(const FrameOfData& in, const BodyTable& table, std::uint64_t clock_hz) {
  MappedFrame out;
  core::MocapFrame& f = out.frame;
  f.frame_number = static_cast<std::uint32_t>(in.frame_number);
  if (clock_hz > 0 && in.mid_exposure_ticks > 0) {
    f.capture_time = core::source_time_from_ns(ticks_to_ns(in.mid_exposure_ticks, clock_hz));
    if (in.transmit_ticks >= in.mid_exposure_ticks) {
      const std::int64_t ns = ticks_to_ns(in.transmit_ticks - in.mid_exposure_ticks, clock_hz);
      if (ns < 3'600'000'000'000) f.source_latency = core::Duration{ns};
    }
  } else if (std::isfinite(in.timestamp_s) && in.timestamp_s >= 0.0 && in.timestamp_s < 1e9) {
    f.capture_time = core::source_time_from_ns(std::llround(in.timestamp_s * 1e9));
    if (std::isfinite(in.software_latency_s) && in.software_latency_s > 0.0f &&
        in.software_latency_s < 3600.0f) {
      f.source_latency = std::chrono::round<core::Duration>(
          std::chrono::duration<double>(static_cast<double>(in.software_latency_s)));
    }
  }
  f.bodies.reserve(in.rigid_bodies.size());
  for (const RigidBodySample& rb : in.rigid_bodies) {
    const auto name = table.names.find(rb.id);
    if (name == table.names.end()) {
      ++out.unknown_ids;
      continue;
    }
    core::BodySample body;
    body.name = name->second;
    if (rb.tracking_valid()) {
      const Eigen::Vector3d p(rb.position[0], rb.position[1], rb.position[2]);
      Eigen::Quaterniond q(rb.orientation[3], rb.orientation[0], rb.orientation[1],
                           rb.orientation[2]);
      const double norm = q.coeffs().norm();
      if (p.allFinite() && q.coeffs().allFinite() && std::abs(norm - 1.0) <= kUnitTolerance) {
        body.tracked = true;
        body.p_world_m = p;
        body.q_world_body = q.normalized();
      } else {
        ++out.invalid_poses;
      }
    }
    f.bodies.push_back(std::move(body));
  }
  return out;
}

Eigen::Vector3d z_up_to_y_up(const Eigen::Vector3d& p) {
  return {p.x(), p.z(), -p.y()};
}

Eigen::Quaterniond z_up_to_y_up(const Eigen::Quaterniond& q) {
  return (z_to_y() * q * z_to_y().conjugate()).normalized();
}

FrameOfData ServedModels::frame_of(const core::MocapFrame& frame, bool y_up,
                                   std::uint64_t clock_hz) {
  FrameOfData out;
  out.frame_number = static_cast<std::int32_t>(frame.frame_number & 0x7FFFFFFFu);
  std::vector<std::string> names;
  names.reserve(frame.bodies.size());
  for (const core::BodySample& b : frame.bodies) {
    auto [it, inserted] = ids_.emplace(b.name, static_cast<std::int32_t>(ids_.size() + 1));
    names.push_back(b.name);
    RigidBodySample rb;
    rb.id = it->second;
    if (b.tracked) {
      const Eigen::Vector3d p = y_up ? z_up_to_y_up(b.p_world_m) : b.p_world_m;
      const Eigen::Quaterniond q = y_up ? z_up_to_y_up(b.q_world_body) : b.q_world_body;
      rb.position = {static_cast<float>(p.x()), static_cast<float>(p.y()),
                     static_cast<float>(p.z())};
      rb.orientation = {static_cast<float>(q.x()), static_cast<float>(q.y()),
                        static_cast<float>(q.z()), static_cast<float>(q.w())};
      rb.params = 0x01;
    }
    out.rigid_bodies.push_back(rb);
  }
  if (listed_ && names != current_) out.params |= kParamModelsChanged;
  listed_ = true;
  current_ = std::move(names);
  const std::int64_t capture_ns = frame.capture_time.time_since_epoch().count();
  out.timestamp_s = static_cast<double>(capture_ns) / 1e9;
  if (clock_hz > 0) {
    out.mid_exposure_ticks = ns_to_ticks(capture_ns, clock_hz);
    const std::int64_t latency_ns = frame.source_latency ? frame.source_latency->count() : 0;
    out.transmit_ticks = ns_to_ticks(capture_ns + latency_ns, clock_hz);
    out.data_received_ticks = out.transmit_ticks;
  }
  return out;
}

ModelDefinitions ServedModels::definitions() {
  listed_ = true;
  ModelDefinitions defs;
  for (const std::string& name : current_) {
    RigidBodyDescription rb;
    rb.name = name;
    rb.id = ids_.at(name);
    defs.rigid_bodies.push_back(std::move(rb));
  }
  return defs;
}

}  // namespace mocaplink::wire::natnet

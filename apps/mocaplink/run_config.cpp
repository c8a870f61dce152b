#include "run_config.hpp"

#include <fstream>
#include <sstream>

#include "mocaplink/config/config_error.hpp"
#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::app {
namespace {

void print(std::FILE* err, const config::ConfigResult& result) {
  for (const auto& e : result.errors) std::fprintf(err, "%s\n", config::to_string(e).c_str());
  for (const auto& w : result.warnings) {
    std::fprintf(err, "warning: %s\n", config::to_string(w).c_str());
  }
}

core::Profile to_core(config::Profile p) {
  switch (p) {
    case config::Profile::px4:
      return core::Profile::px4;
    case config::Profile::ardupilot:
      return core::Profile::ardupilot;
    case config::Profile::px4_gps:
      return core::Profile::px4_gps;
    case config::Profile::ardupilot_gps:
      return core::Profile::ardupilot_gps;
    case config::Profile::classic:
      return core::Profile::classic;
    case config::Profile::custom:
      return core::Profile::custom;
  }
  return core::Profile::custom;
}

core::MessageKind to_core(config::MessageKind k) {
  switch (k) {
    case config::MessageKind::odometry:
      return core::MessageKind::odometry;
    case config::MessageKind::vision_position_estimate:
      return core::MessageKind::vision_position_estimate;
    case config::MessageKind::vision_speed_estimate:
      return core::MessageKind::vision_speed_estimate;
    case config::MessageKind::att_pos_mocap:
      return core::MessageKind::att_pos_mocap;
    case config::MessageKind::hil_gps:
      return core::MessageKind::hil_gps;
    case config::MessageKind::gps_input:
      return core::MessageKind::gps_input;
    case config::MessageKind::local_position_ned:
      return core::MessageKind::local_position_ned;
  }
  return core::MessageKind::odometry;
}

std::vector<core::MessageKind> to_core(const std::vector<config::MessageKind>& kinds) {
  std::vector<core::MessageKind> out;
  out.reserve(kinds.size());
  for (const auto k : kinds) out.push_back(to_core(k));
  return out;
}

core::TrackerConfig to_core(const config::TrackingSettings& t) {
  core::TrackerConfig c;  // the core's defaults, overridden by what the file sets
  if (t.loss_timeout_ms) c.loss_timeout_ms = *t.loss_timeout_ms;
  if (t.reset_after_ms) c.reset_after_ms = *t.reset_after_ms;
  if (t.position_noise_m) c.position_noise_m = *t.position_noise_m;
  if (t.attitude_noise_rad) c.attitude_noise_rad = *t.attitude_noise_rad;
  if (t.accel_noise_mps2) c.accel_noise_mps2 = *t.accel_noise_mps2;
  if (t.angular_accel_noise_radps2) c.angular_accel_noise_radps2 = *t.angular_accel_noise_radps2;
  if (t.gate_sigma) c.gate_sigma = *t.gate_sigma;
  if (t.gate_min_m) c.gate_min_m = *t.gate_min_m;
  if (t.jump_confirm_frames) c.jump_confirm_frames = *t.jump_confirm_frames;
  return c;
}

/// Full MAVLink 2 frame size of a message kind (header 10 + payload + CRC 2).
std::size_t frame_bytes(core::MessageKind kind) {
  std::size_t payload = 0;
  switch (kind) {
    case core::MessageKind::odometry:
      payload = mavlink::Odometry::kMaxLength;
      break;
    case core::MessageKind::vision_position_estimate:
      payload = mavlink::VisionPositionEstimate::kMaxLength;
      break;
    case core::MessageKind::vision_speed_estimate:
      payload = mavlink::VisionSpeedEstimate::kMaxLength;
      break;
    case core::MessageKind::att_pos_mocap:
      payload = mavlink::AttPosMocap::kMaxLength;
      break;
    case core::MessageKind::hil_gps:
      payload = mavlink::HilGps::kMaxLength;
      break;
    case core::MessageKind::gps_input:
      payload = mavlink::GpsInput::kMaxLength;
      break;
    case core::MessageKind::local_position_ned:
      payload = mavlink::LocalPositionNed::kMaxLength;
      break;
  }
  return mavlink::kHeaderSizeV2 + payload + mavlink::kChecksumSize;
}

}  // namespace

std::optional<config::Config> load_run_config(const RunOptions& options,
                                              const config::SourceValidator& validate_source,
                                              std::FILE* err) {
  config::CommandLineOverrides overrides;
  overrides.source = options.source;
  overrides.http = options.http;
  overrides.vehicles = options.vehicles;
  config::ConfigResult result;
  std::string name = "built-in demo";
  // The demo is only for a run that names no source and no vehicle at all: any --config, --source
  // or --vehicle starts from what the user gave, so no demo vehicle ever sends Body1's poses to
  // 127.0.0.1:14550 (where QGroundControl and simulators listen) behind the user's back.
  const bool demo = !options.config_file && !options.source && options.vehicles.empty();
  if (options.config_file) {
    name = *options.config_file;
    std::ifstream in(*options.config_file, std::ios::binary);
    if (!in) {
      std::fprintf(err, "%s: cannot read the configuration file\n", name.c_str());
      return std::nullopt;
    }
    std::ostringstream text;
    text << in.rdbuf();
    result = config::load_config(text.str(), name, overrides, validate_source);
  } else if (demo) {
    result = config::apply_overrides(config::demo_config(), overrides, name, validate_source);
  } else if (!options.source) {
    std::fprintf(err,
                 "mocaplink run: --vehicle needs a mocap source: give --source URL or --config "
                 "FILE (the demo runs only without --config, --source and --vehicle); nothing "
                 "was sent\n");
    return std::nullopt;
  } else {
    name = "command line";
    result = config::load_config("", name, overrides, validate_source);
  }
  print(err, result);
  if (!result.ok()) {
    const std::size_t n = result.errors.size();
    std::fprintf(err, "mocaplink run: %zu error%s in the configuration (%s); nothing was sent\n", n,
                 n == 1 ? "" : "s", name.c_str());
    return std::nullopt;
  }
  return std::move(result.config);
}

std::optional<core::BridgeConfig> make_bridge_config(const config::Config& cfg,
                                                     std::string& error) {
  core::BridgeConfig out;
  const auto world = core::WorldAxisMapping::parse(config::to_string(cfg.mocap.up),
                                                   config::to_string(cfg.mocap.north));
  if (!world) {
    error = "[mocap] " + world.error().field + ": " + world.error().message;
    return std::nullopt;
  }
  out.world = *world;
  if (cfg.origin) {
    out.origin = core::GeodeticPosition{cfg.origin->latitude_deg, cfg.origin->longitude_deg,
                                        cfg.origin->altitude_m};
  }
  out.tracking = to_core(cfg.tracking);
  for (std::size_t i = 0; i < cfg.vehicles.size(); ++i) {
    auto spec = make_vehicle_spec(cfg.vehicles[i], i, error);
    if (!spec) return std::nullopt;
    out.vehicles.push_back(std::move(*spec));
  }
  return out;
}

std::optional<core::VehicleSpec> make_vehicle_spec(const config::Vehicle& v, std::size_t slot,
                                                   std::string& error) {
  const auto axes =
      core::BodyAxisMapping::parse(config::to_string(v.body_forward), config::to_string(v.body_up));
  if (!axes) {
    error = "vehicle " + v.name + ": " + axes.error().field + ": " + axes.error().message;
    return std::nullopt;
  }
  core::VehicleSpec spec;
  spec.name = v.name;
  spec.body = v.body;
  spec.system_id = v.system_id;
  spec.component_id = v.component_id;
  spec.profile = to_core(v.profile);
  spec.messages = to_core(v.messages);
  spec.rate_hz = v.rate_hz;
  spec.signing_key = v.signing_key;
  // One physical channel per vehicle (mavlink-wire.md §7.3): link ids 1, 2, ... by slot
  // (wrapping after 255 is harmless: each vehicle is its own link).
  spec.signing_link_id = static_cast<std::uint8_t>((slot % 255) + 1);
  spec.body_axes = *axes;
  spec.enabled = v.enabled;
  return spec;
}

double profile_bytes_per_second(const config::Vehicle& vehicle) {
  const std::size_t signature = vehicle.signing_key ? mavlink::kSignatureSize : 0;
  const auto set = core::messages_for(to_core(vehicle.profile), to_core(vehicle.messages));
  double per_send = 0.0;
  for (std::size_t k = 0; k < core::kMessageKindCount; ++k) {
    const auto kind = static_cast<core::MessageKind>(k);
    if (set.contains(kind)) per_send += static_cast<double>(frame_bytes(kind) + signature);
  }
  // 1 Hz each: HEARTBEAT, a TIMESYNC request and reply, SET_GPS_GLOBAL_ORIGIN.
  const double clock_driven =
      static_cast<double>(mavlink::kHeaderSizeV2 + mavlink::kChecksumSize + signature) * 4.0 +
      static_cast<double>(mavlink::Heartbeat::kMaxLength + 2 * mavlink::Timesync::kMaxLength +
                          mavlink::SetGpsGlobalOrigin::kMaxLength);
  return per_send * vehicle.rate_hz + clock_driven;
}

}  // namespace mocaplink::app

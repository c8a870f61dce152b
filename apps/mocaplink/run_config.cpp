#include "run_config.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "mocaplink/config/config_error.hpp"
#include "mocaplink/config/demo.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/ros2/publisher.hpp"

namespace mocaplink::app {
namespace {

void print(std::FILE* err, const config::ConfigResult& result) {
  for (const auto& e : result.errors) std::fprintf(err, "%s\n", config::to_string(e).c_str());
  for (const auto& w : result.warnings) {
    std::fprintf(err, "warning: %s\n", config::to_string(w).c_str());
  }
}

}  // namespace

std::optional<config::Config> load_run_config(const RunOptions& options,
                                              const config::SourceValidator& validate_source,
                                              std::FILE* err) {
  config::CommandLineOverrides overrides;
  overrides.source = options.source;
  overrides.http = options.http;
  overrides.http_allow_hosts = options.http_allow_hosts;
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

std::optional<Ros2Domain> resolve_ros2(const config::Config& config, std::string& error) {
  if (!ros2::available()) {
    error = "[ros2]: this build cannot publish to ROS 2 (" + ros2::implementation() +
            "); remove [ros2], or run mocaplink on Linux (amd64, arm64, armhf)";
    return std::nullopt;
  }
  if (config.ros2->domain_id) return Ros2Domain{*config.ros2->domain_id, "[ros2] domain_id"};
  const char* env = std::getenv("ROS_DOMAIN_ID");
  if (env == nullptr || *env == '\0') return Ros2Domain{0, "the default"};
  auto parsed = config::parse_ros_domain_id(env);
  if (!parsed) {
    error = "[ros2]: no domain_id, and " + parsed.error();
    return std::nullopt;
  }
  return Ros2Domain{parsed.value(), "ROS_DOMAIN_ID"};
}

std::optional<core::BridgeConfig> make_bridge_config(const config::Config& cfg,
                                                     std::string& error) {
  core::BridgeConfig out;
  const auto world = core::WorldAxisMapping::make(cfg.mocap.up, cfg.mocap.north);
  if (!world) {
    error = "[mocap] " + world.error().field + ": " + world.error().message;
    return std::nullopt;
  }
  out.world = *world;
  // The up axis each system streams by default (docs/sources.md), for the agreement's axis fix.
  const std::string& scheme = cfg.mocap.source.scheme;
  if (scheme == "vicon" || scheme == "qtm" || scheme == "vicon-udp")
    out.source_up = core::axis::pos_z;
  if (scheme == "natnet") out.source_up = core::axis::pos_y;
  out.origin = cfg.origin;
  out.tracking = cfg.tracking;
  for (const config::Vehicle& vehicle : cfg.vehicles) out.vehicles.push_back(vehicle.spec);
  if (cfg.ros2) {
    const auto axes = core::BodyAxisMapping::make(cfg.mocap.body_forward, cfg.mocap.body_up);
    if (!axes) {
      error = "[mocap] " + axes.error().field + ": " + axes.error().message;
      return std::nullopt;
    }
    out.published.enabled = true;
    out.published.all = cfg.ros2->bodies.empty();
    out.published.names = cfg.ros2->bodies;
    out.published.axes = *axes;
  }
  return out;
}

}  // namespace mocaplink::app

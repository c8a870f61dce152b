// `mocaplink run`: command-line options → a validated Config (or every problem, printed), and
// Config → the core's BridgeConfig. Exit-code policy: any problem here is bad input (exit 1) and
// happens before a socket is opened, so nothing is sent.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/config/config.hpp"
#include "mocaplink/core/bridge.hpp"

namespace mocaplink::app {

/// The options of `mocaplink run` as given (DESIGN.md "Command line").
struct RunOptions {
  std::optional<std::string>
      config_file;                    ///< --config FILE (none, no --source, no --vehicle: the demo)
  std::optional<std::string> source;  ///< --source URL
  std::vector<std::string> vehicles;  ///< --vehicle SPEC, in order
  std::optional<std::string> http;    ///< --http ADDR
  std::vector<std::string> http_allow_hosts;  ///< --http-allow-host NAME, in order
  std::optional<std::string> record_dir;      ///< --record DIR
};

/// Reads the file (if any) and applies the overrides. The built-in demo is the base only when
/// neither a file, --source nor --vehicle is given (--http still applies to it); otherwise the
/// configuration is exactly what the file and the options say. Prints every error ("FILE:LINE:COL:
/// key: message") and warning ("warning: ...") to `err`. nullopt when the configuration is
/// unusable. The source is judged by `validate_source` (the source registry's, as for `check`).
[[nodiscard]] std::optional<config::Config> load_run_config(
    const RunOptions& options, const config::SourceValidator& validate_source, std::FILE* err);

/// The core's view of a validated Config. Errors here would be bugs in the config library
/// (which checks the same rules) and are returned as text.
/// [ros2]'s domain and where it came from.
struct Ros2Domain {
  std::uint32_t id = 0;
  std::string from;  ///< "[ros2] domain_id", "ROS_DOMAIN_ID" or "the default"
};
/// The domain [ros2] publishes on: its domain_id, else ROS_DOMAIN_ID (as rcl reads it), else 0.
/// nullopt and `error` when ROS_DOMAIN_ID is bad or this build has no ROS 2 (no DDS library on
/// its platform). Precondition: config.ros2.
[[nodiscard]] std::optional<Ros2Domain> resolve_ros2(const config::Config& config,
                                                     std::string& error);

[[nodiscard]] std::optional<core::BridgeConfig> make_bridge_config(const config::Config& config,
                                                                   std::string& error);

}  // namespace mocaplink::app

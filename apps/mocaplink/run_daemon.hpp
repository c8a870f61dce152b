// The `mocaplink run` daemon: one event loop (standalone Asio) owning the core Bridge, one Link per
// vehicle, the mocap Source on its own thread feeding a bounded queue, optional recording, signing
// timestamp persistence, periodic summaries and a clean stop on SIGINT/SIGTERM (docs/daemon.md).
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>

#include "mocaplink/config/config.hpp"
#include "mocaplink/sources/registry.hpp"

namespace mocaplink::app {

/// Exit codes of `mocaplink run` (commands.hpp, docs/daemon.md).
inline constexpr int kExitClean = 0;     ///< stopped by a signal, or the source finished
inline constexpr int kExitBadInput = 1;  ///< bad config / CLI / source URL; nothing was sent
inline constexpr int kExitRuntime = 2;   ///< an I/O failure at start-up (files, ports)

struct DaemonSettings {
  config::Config config;
  std::optional<std::filesystem::path> record_dir;  ///< --record DIR
  std::filesystem::path state_dir;                  ///< signing timestamps (io::SigningStore)
  std::chrono::milliseconds summary_period{std::chrono::seconds(10)};
  bool http_requested = false;  ///< --http given on the command line
  /// [ros2]'s domain: the file's domain_id, else ROS_DOMAIN_ID, else 0 (cmd_run resolves it).
  std::uint32_t ros2_domain_id = 0;
};

/// Runs until SIGINT/SIGTERM (or the source finishes) and returns the exit code. Logs go to the
/// default spdlog logger. The source is opened through `sources`.
[[nodiscard]] int run_daemon(const DaemonSettings& settings,
                             const sources::SourceRegistry& sources);

}  // namespace mocaplink::app

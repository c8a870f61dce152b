// `mocaplink run [--config FILE] [--source URL] [--vehicle SPEC]... [--http ADDR] [--record DIR]`
// (DESIGN.md "Command line"; behaviour, logs and exit codes in docs/daemon.md). Neither --config,
// --source nor --vehicle: the demo (simulated source, one vehicle at udp://127.0.0.1:14550).
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "mocaplink/config/net_address.hpp"
#include "mocaplink/io/signing_store.hpp"
#include "run_config.hpp"
#include "run_daemon.hpp"

namespace mocaplink::app {
namespace {

/// Logs go to stderr with a level; MOCAPLINK_LOG_LEVEL=trace|debug|info|warn|error|off.
void setup_logging() {
  auto logger = spdlog::stderr_color_mt("mocaplink");
  logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%l%$ %v");
  auto level = spdlog::level::info;
  if (const char* text = std::getenv("MOCAPLINK_LOG_LEVEL"); text != nullptr && *text != '\0') {
    level = spdlog::level::from_str(text);
  }
  logger->set_level(level);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(std::move(logger));
}

/// MOCAPLINK_SUMMARY_S: seconds between summary lines (default 10; tests use less).
std::chrono::milliseconds summary_period() {
  if (const char* text = std::getenv("MOCAPLINK_SUMMARY_S"); text != nullptr) {
    char* end = nullptr;
    const double s = std::strtod(text, &end);
    if (end != text && s >= 0.1 && s <= 3600.0) {
      return std::chrono::milliseconds(static_cast<std::int64_t>(s * 1000.0));
    }
  }
  return std::chrono::seconds(10);
}

int run_command(const RunOptions& options, const sources::SourceRegistry& sources) {
  auto config = load_run_config(options, sources.validator(), stderr);
  if (!config) return kExitBadInput;
  setup_logging();
  DaemonSettings settings;
  settings.config = std::move(*config);
  if (options.record_dir) settings.record_dir = *options.record_dir;
  settings.state_dir = io::default_state_dir();
  settings.summary_period = summary_period();
  settings.http_requested = options.http.has_value();
  spdlog::info("mocaplink {}: source {}, {} vehicle{}", MOCAPLINK_VERSION,
               settings.config.mocap.source.text, settings.config.vehicles.size(),
               settings.config.vehicles.size() == 1 ? "" : "s");
  if (settings.config.vehicles.empty()) {
    spdlog::warn("no vehicle configured: nothing is sent until one is added from the dashboard");
  }
  return run_daemon(settings, sources);
}

}  // namespace

void add_run_commands(CLI::App& app, ExitCode& exit_code, const sources::SourceRegistry& sources) {
  auto* run = app.add_subcommand(
      "run", "Run the bridge: mocap source -> MAVLink to every vehicle (no arguments: the demo)");
  auto options = std::make_shared<RunOptions>();
  run->add_option("--config", options->config_file, "TOML configuration file (docs/config.md)");
  run->add_option("--source", options->source,
                  "Mocap source URL, replacing [mocap] source (e.g. vicon://192.168.1.3)");
  run->add_option("--vehicle", options->vehicles,
                  "Add or change a vehicle: NAME:key=value,... with [[vehicle]] keys "
                  "(e.g. quad1:body=Quad1,link=udp://127.0.0.1:14540,profile=px4)")
      ->allow_extra_args(false);
  run->add_option("--http", options->http, "Dashboard address HOST:PORT, replacing [http] listen");
  run->add_option("--record", options->record_dir,
                  "Record mocap frames (DIR/mocap.csv) and MAVLink traffic (DIR/<vehicle>.tlog)");
  run->callback(
      [options, &exit_code, &sources] { exit_code.value = run_command(*options, sources); });
}

}  // namespace mocaplink::app

// Subcommand families of the `mocaplink` binary. Each add_* registers its subcommands on the app;
// the callbacks run the command and set the process exit code through the returned reference.
// Exit codes: 0 success, 1 bad input or config (nothing sent), 2 runtime failure (I/O); `vehicle
// setup` adds 3: the vehicle's set-up blocks.
#pragma once

#include <CLI/CLI.hpp>

#include "mocaplink/sources/registry.hpp"

namespace mocaplink::app {

/// Where a subcommand stores its exit code (main returns it after parsing and running).
struct ExitCode {
  int value = 0;
};

/// `mavlink encode|decode|listen` (cmd_mavlink.cpp).
void add_mavlink_commands(CLI::App& app, ExitCode& exit_code);
// The commands that take a source URL get main()'s source registry, which must outlive parsing.

/// `bodies`, `record` (cmd_station.cpp).
void add_station_commands(CLI::App& app, ExitCode& exit_code,
                          const sources::SourceRegistry& sources);
/// `serve` (cmd_serve.cpp).
void add_serve_commands(CLI::App& app, ExitCode& exit_code, const sources::SourceRegistry& sources);
/// `check` (cmd_check.cpp).
void add_config_commands(CLI::App& app, ExitCode& exit_code,
                         const sources::SourceRegistry& sources);
/// `vehicle setup` (cmd_vehicle.cpp).
void add_vehicle_commands(CLI::App& app, ExitCode& exit_code,
                          const sources::SourceRegistry& sources);
/// `run` (cmd_run.cpp).
void add_run_commands(CLI::App& app, ExitCode& exit_code, const sources::SourceRegistry& sources);

}  // namespace mocaplink::app

// Subcommand families of the `mocaplink` binary. Each add_* registers its subcommands on the app;
// the callbacks run the command and set the process exit code through the returned reference.
// Exit codes: 0 success, 1 bad input or config (nothing sent), 2 runtime failure (I/O).
#pragma once

#include <CLI/CLI.hpp>

namespace mocaplink::app {

/// Where a subcommand stores its exit code (main returns it after parsing and running).
struct ExitCode {
  int value = 0;
};

void add_mavlink_commands(CLI::App& app, ExitCode& exit_code);

}  // namespace mocaplink::app

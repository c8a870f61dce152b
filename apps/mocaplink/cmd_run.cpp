// Subcommands registered by add_run_commands (see commands.hpp). Nothing registered yet.
#include "commands.hpp"

namespace mocaplink::app {

void add_run_commands(CLI::App& app, ExitCode& exit_code) {
  (void)app;
  (void)exit_code;
}

}  // namespace mocaplink::app

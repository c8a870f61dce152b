// `mocaplink mavlink encode|decode|listen` (DESIGN.md "Command line"). Filled in by issue 2.
#include "commands.hpp"

namespace mocaplink::app {

void add_mavlink_commands(CLI::App& app, ExitCode& exit_code) {
  (void)exit_code;
  auto* mavlink = app.add_subcommand("mavlink", "MAVLink tools: encode, decode, listen");
  mavlink->require_subcommand(1);
}

}  // namespace mocaplink::app

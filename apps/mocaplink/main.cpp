// mocaplink — motion capture to MAVLink. main() builds the command tree; each subcommand's
// implementation lives in its own cmd_*.cpp (see commands.hpp for exit codes).
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mocaplink: motion capture (Vicon, OptiTrack, Qualisys, VRPN) to MAVLink vehicles"};
  // The same command line on every platform: on Windows CLI11 would otherwise also take "/x" as an
  // option, and then a path such as /tmp/lab.toml (or Z:-less paths under Wine) as a stray flag.
  app.allow_windows_style_options(false);
  app.set_version_flag("--version", MOCAPLINK_VERSION);
  app.require_subcommand(1);
  mocaplink::app::ExitCode exit_code;
  const auto sources = mocaplink::sources::builtin_sources();
  mocaplink::app::add_run_commands(app, exit_code, sources);
  mocaplink::app::add_config_commands(app, exit_code, sources);
  mocaplink::app::add_station_commands(app, exit_code, sources);
  mocaplink::app::add_serve_commands(app, exit_code, sources);
  mocaplink::app::add_mavlink_commands(app, exit_code);
  mocaplink::app::add_vehicle_commands(app, exit_code, sources);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints help/usage errors; bad command lines exit 1 (bad input), --help exits 0.
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mocaplink: %s\n", e.what());
    return 2;
  }
  return exit_code.value;
}

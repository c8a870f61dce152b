// `mocaplink run [--config FILE] [--source URL] [--vehicle SPEC]... [--http ADDR]
// [--http-allow-host NAME]... [--record DIR]` (DESIGN.md "Command line"; behaviour, logs and exit
// codes in docs/daemon.md). Neither --config,
// --source nor --vehicle: the demo (simulated source, one vehicle at udp://127.0.0.1:14550).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "mocaplink/config/net_address.hpp"
#include "mocaplink/io/rotating_file.hpp"
#include "mocaplink/io/signing_store.hpp"
#include "run_config.hpp"
#include "run_daemon.hpp"

namespace mocaplink::app {
namespace {

/// A spdlog sink into an io::RotatingFile (the Windows log file; see setup_logging).
class RotatingFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit RotatingFileSink(std::unique_ptr<io::RotatingFile> file) : file_(std::move(file)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    spdlog::memory_buf_t line;
    formatter_->format(msg, line);
    file_->write(std::string_view(line.data(), line.size()));
  }
  void flush_() override { file_->flush(); }

 private:
  std::unique_ptr<io::RotatingFile> file_;
};

/// Log file size and how many older files are kept (Windows): at most 4 × 10 MiB.
constexpr std::size_t kLogFileBytes = 10 * 1024 * 1024;
constexpr std::size_t kLogFilesKept = 3;

/// Logs go to stderr with a level; MOCAPLINK_LOG_LEVEL=trace|debug|info|warn|error|off. On
/// Windows also to STATE_DIR\logs\mocaplink.log (%LOCALAPPDATA%\mocaplink\logs by default):
/// there is no journal there, and a closed console window takes its text with it.
void setup_logging(const std::filesystem::path& state_dir) {
  std::vector<spdlog::sink_ptr> sinks{std::make_shared<spdlog::sinks::stderr_color_sink_mt>()};
  std::string file_problem;
  std::filesystem::path log_file;
#ifdef _WIN32
  auto file = std::make_unique<io::RotatingFile>(state_dir / "logs" / "mocaplink.log",
                                                 kLogFileBytes, kLogFilesKept);
  if (file->ok()) {
    log_file = file->path();
    sinks.push_back(std::make_shared<RotatingFileSink>(std::move(file)));
  } else {
    file_problem = file->error();
  }
#else
  (void)state_dir;
#endif
  auto logger = std::make_shared<spdlog::logger>("mocaplink", sinks.begin(), sinks.end());
  logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%l%$ %v");
  auto level = spdlog::level::info;
  if (const char* text = std::getenv("MOCAPLINK_LOG_LEVEL"); text != nullptr && *text != '\0') {
    level = spdlog::level::from_str(text);
  }
  logger->set_level(level);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(std::move(logger));
  if (!log_file.empty()) spdlog::info("log file: {}", log_file.string());
  if (!file_problem.empty()) spdlog::warn("no log file: {}", file_problem);
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
  DaemonSettings settings;
  settings.state_dir = io::default_state_dir();
  setup_logging(settings.state_dir);
  settings.config = std::move(*config);
  if (options.record_dir) settings.record_dir = *options.record_dir;
  settings.summary_period = summary_period();
  settings.http_requested = options.http.has_value();
  if (settings.config.ros2) {
    std::string error;
    const auto domain = resolve_ros2(settings.config, error);
    if (!domain) {
      spdlog::error("configuration: {}; nothing was sent", error);
      return kExitBadInput;
    }
    settings.ros2_domain_id = domain->id;
  }
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
  run->add_option("--http-allow-host", options->http_allow_hosts,
                  "A name (NAME or NAME:PORT) besides localhost and 127.0.0.1 by which the "
                  "dashboard may be opened, added to [http] allowed_hosts; repeatable")
      ->allow_extra_args(false);
  run->add_option("--record", options->record_dir,
                  "Record mocap frames (DIR/mocap.csv) and MAVLink traffic (DIR/<vehicle>.tlog)");
  run->callback(
      [options, &exit_code, &sources] { exit_code.value = run_command(*options, sources); });
}

}  // namespace mocaplink::app

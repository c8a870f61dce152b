// `mocaplink check FILE`: validates a configuration without running anything. Prints every error
// (stderr, "FILE:LINE:COL: key: message") and exits 1, or prints a summary (stdout) and exits 0.
// `run` joins this file with issue 5.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "mocaplink/config/config_error.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/ros2/publisher.hpp"
#include "mocaplink/sources/registry.hpp"
#include "run_config.hpp"

namespace mocaplink::app {
namespace {

/// The whole file, or std::nullopt with `error` set to the system's reason.
std::optional<std::string> read_file(const std::string& path, std::string& error) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) {
    error = std::strerror(errno);
    return std::nullopt;
  }
  std::string text;
  char buffer[65536];
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    text.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get()) != 0) {
    error = std::strerror(errno);
    return std::nullopt;
  }
  return text;
}

void print_summary(const config::Config& cfg) {
  const std::size_t n = cfg.vehicles.size();
  std::printf("ok: %zu vehicle%s, source %s\n", n, n == 1 ? "" : "s",
              cfg.mocap.source.text.c_str());
  for (const auto& v : cfg.vehicles) {
    std::printf("  %s: body %s, %s, system_id %u, profile %s, %g Hz%s%s\n", v.spec.name.c_str(),
                v.spec.body.c_str(), config::to_string(v.link).c_str(),
                static_cast<unsigned>(v.spec.system_id),
                std::string(core::to_string(v.spec.profile)).c_str(), v.spec.rate_hz,
                v.spec.signing_key ? ", signed" : "", v.spec.enabled ? "" : ", disabled");
  }
  // Ground stations share the vehicle's link: what it carries, and what is left once mocaplink's
  // own traffic (poses first) is served (issue 38; docs/config.md "Ground stations").
  for (const auto& v : cfg.vehicles) {
    if (v.gcs.empty()) continue;
    std::string endpoints;
    for (const auto& g : v.gcs) endpoints += (endpoints.empty() ? "" : ", ") + config::to_string(g);
    std::printf("  %s: ground stations at %s\n", v.spec.name.c_str(), endpoints.c_str());
    const double own = core::link_bytes_per_second(
        v.spec.profile, core::messages_for(v.spec.profile, v.spec.messages), v.spec.rate_hz,
        v.spec.signing_key.has_value());
    if (v.link.kind == config::LinkKind::serial) {
      const double capacity = core::serial_bytes_per_second(v.link.baud);
      std::printf(
          "  %s: link budget %.0f bytes/s (%u baud); mocaplink uses up to %.0f, ground stations "
          "get the rest (%.0f), poses first\n",
          v.spec.name.c_str(), capacity, v.link.baud, own, std::max(0.0, capacity - own));
    } else {
      std::printf(
          "  %s: link budget not known (%s); mocaplink uses up to %.0f bytes/s, ground stations "
          "what the network carries besides, poses first\n",
          v.spec.name.c_str(), config::to_string(v.link.kind), own);
    }
  }
  // The vision profiles send the same ODOMETRY; auto also checks the set-up by the rules of the
  // autopilot the vehicle turns out to run (docs/setup.md).
  for (const auto& v : cfg.vehicles) {
    if (v.spec.profile != core::Profile::px4 && v.spec.profile != core::Profile::ardupilot)
      continue;
    std::printf(
        "  hint: %s: profile = \"auto\" sends the same and checks the vehicle's set-up by "
        "whichever autopilot it runs\n",
        v.spec.name.c_str());
  }
  std::string names;
  for (const auto& host : cfg.http.allowed_hosts) {
    names += (names.empty() ? ", also opened as " : ", ") +
             (host.port == 0 ? config::to_string(config::HostPort{host.host, cfg.http.listen.port})
                             : config::to_string(host));
  }
  std::printf("  dashboard: http://%s%s%s\n", config::to_string(cfg.http.listen).c_str(),
              cfg.http.token.empty() ? "" : " (token required)", names.c_str());
}

void print_ros2(const config::Ros2Settings& ros2, const Ros2Domain& domain) {
  std::string what;
  for (const auto& [on, name] : {std::pair{ros2.pose, "pose"}, std::pair{ros2.odom, "odom"}}) {
    if (on) what += (what.empty() ? "" : ", ") + core::ros_body_topic(ros2.ns, "BODY", name);
  }
  if (ros2.tf) what += (what.empty() ? "" : ", ") + std::string("/tf");
  if (what.empty()) what = "no body topics (the ros2:// links only)";
  std::string bodies = "every body the source streams";
  if (!ros2.bodies.empty()) {
    bodies.clear();
    for (const auto& b : ros2.bodies) bodies += (bodies.empty() ? "" : ", ") + b;
  }
  std::printf("  ros2: domain %u (%s), %s; %s; world frame %s, axes %s; interface %s; %s\n",
              domain.id, domain.from.c_str(), what.c_str(), bodies.c_str(), ros2.frame_id.c_str(),
              std::string(core::to_string(ros2.axes)).c_str(), ros2.network_interface.c_str(),
              ros2::implementation().c_str());
}

int run_check(const std::string& path, const sources::SourceRegistry& sources) {
  std::string error;
  const auto text = read_file(path, error);
  if (!text) {
    std::fprintf(stderr, "mocaplink check: cannot read %s: %s\n", path.c_str(), error.c_str());
    return 1;
  }
  // The source is judged by the same registry `run` opens it with: they agree by construction.
  const auto result = config::parse_config(*text, path, sources.validator());
  for (const auto& e : result.errors) std::fprintf(stderr, "%s\n", config::to_string(e).c_str());
  for (const auto& warning : result.warnings) {
    std::fprintf(stderr, "warning: %s\n", config::to_string(warning).c_str());
  }
  if (!result.ok()) {
    const std::size_t n = result.errors.size();
    std::fprintf(stderr, "%s: %zu error%s\n", path.c_str(), n, n == 1 ? "" : "s");
    return 1;
  }
  std::optional<Ros2Domain> domain;
  if (result.config->ros2 && !(domain = resolve_ros2(*result.config, error))) {
    std::fprintf(stderr, "%s: %s\n%s: 1 error\n", path.c_str(), error.c_str(), path.c_str());
    return 1;
  }
  print_summary(*result.config);
  if (domain) print_ros2(*result.config->ros2, *domain);
  return 0;
}

}  // namespace

void add_config_commands(CLI::App& app, ExitCode& exit_code,
                         const sources::SourceRegistry& sources) {
  auto* check = app.add_subcommand(
      "check", "Validate a configuration file: every error with FILE:LINE:COL; exit 1 on errors");
  auto path = std::make_shared<std::string>();
  check->add_option("FILE", *path, "TOML configuration file")->required();
  check->callback([path, &exit_code, &sources] { exit_code.value = run_check(*path, sources); });
}

}  // namespace mocaplink::app

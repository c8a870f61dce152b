// `mocaplink vehicle setup --config FILE NAME [--apply] [--json] [--timeout S]` (issue 28;
// docs/setup.md): opens the vehicle's link from the configuration, reads its set-up list as `run`
// does (core::VehicleSetup) and prints it; with --apply writes the fixes of the wrong items it
// printed, never to an armed vehicle, and prints the list again. Nothing else is sent but a 1 Hz
// HEARTBEAT (as the vehicle's component 197, so that a vehicle serving UDP learns where to answer):
// no pose, no TIMESYNC, no origin (an ArduPilot takes an origin once per boot: only `run` sets it).
//
// Exit codes: 0 nothing blocks; 1 bad command line or configuration; 2 the vehicle was not heard,
// or answered no parameter read, within --timeout; 3 something blocks (or a write failed).
#include <algorithm>
#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "mocaplink/config/load.hpp"
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/sender.hpp"
#include "mocaplink/core/vehicle_setup.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/web/bridge_views.hpp"
#include "mocaplink/web/status_json.hpp"
#include "run_links.hpp"

namespace mocaplink::app {
namespace {

constexpr auto kTick = std::chrono::milliseconds(100);

struct Options {
  std::string config_path;
  std::string name;
  bool apply = false;
  bool json = false;
  double timeout_s = 30.0;
};

std::string format_value(const std::optional<double>& v) {
  if (!v) return "-";
  std::ostringstream out;
  out << *v;
  return out.str();
}

/// The list as text: one line per item, the words of the vehicle, the delay.
void print_text(const web::VehicleView& v) {
  std::printf("vehicle %s: %s%s, set-up %s\n", v.name.c_str(), v.autopilot.name.c_str(),
              v.autopilot.version ? (" " + *v.autopilot.version).c_str() : "",
              v.setup.state.c_str());
  for (const web::SetupItemView& i : v.setup.items) {
    const std::string mark = i.status == "ok" ? "ok" : i.severity;
    std::printf(
        "  %-9s %-16s now %-6s needed %s%s\n", mark.c_str(), i.parameter.c_str(),
        format_value(i.current).c_str(), i.needed.c_str(),
        i.apply != "none"
            ? (" [" + i.apply + (i.apply_note.empty() ? "" : ": ") + i.apply_note + "]").c_str()
            : "");
    if (i.status != "ok")
      std::printf("            %s%s\n", i.why.c_str(), i.reboot ? " (after a reboot)" : "");
  }
  if (!v.delay_ms.parameter.empty() && v.delay_ms.recommended) {
    std::printf("  delay: %s recommended %s ms (%s)\n", v.delay_ms.parameter.c_str(),
                format_value(v.delay_ms.recommended).c_str(), v.delay_ms.basis.c_str());
  }
  if (v.estimator && !v.estimator->problems.empty()) {
    std::string problems;
    for (const auto& p : v.estimator->problems) problems += (problems.empty() ? "" : ", ") + p;
    std::printf("  estimator (%s): %s\n", v.estimator->source.c_str(), problems.c_str());
  }
  for (const web::StatusTextView& t : v.statustext) {
    std::printf("  vehicle says (%s): %s\n", t.severity.c_str(), t.text.c_str());
  }
  if (!v.setup.reboot_for.empty()) {
    std::string names;
    for (const auto& n : v.setup.reboot_for) names += (names.empty() ? "" : ", ") + n;
    std::printf("  reboot the vehicle for %s to take effect\n", names.c_str());
  }
}

/// The fields of GET /api/vehicles/NAME that describe the set-up (docs/api.md).
void print_json(const web::VehicleView& v) {
  const nlohmann::json all = v;
  nlohmann::json out;
  out["name"] = v.name;
  for (const char* key : {"autopilot", "setup", "statustext", "estimator", "delay_ms"}) {
    out[key] = all.at(key);
  }
  std::printf("%s\n", out.dump(2).c_str());
}

class SetupSession {
 public:
  SetupSession(const config::Vehicle& vehicle, const Options& options)
      : options_(options),
        vehicle_(vehicle),
        state_([&] {
          core::VehicleStateConfig c;
          c.system_id = vehicle.spec.system_id;
          return c;
        }()),
        setup_(vehicle.spec.system_id, vehicle.spec.component_id, vehicle.spec.profile,
               core::messages_for(vehicle.spec.profile, vehicle.spec.messages)),
        sender_([&] {
          core::SenderConfig c;
          c.system_id = vehicle.spec.system_id;
          c.component_id = vehicle.spec.component_id;
          c.signing_key = vehicle.spec.signing_key;
          c.signing_link_id = 1;
          return c;
        }()),
        timer_(loop_) {}

  int run() {
    link_ = make_vehicle_link(loop_, vehicle_);
    link_.link->start(
        [this](const mavlink::FrameView& frame, core::HostTime t) { on_frame(frame, t); }, {});
    started_ = io::host_now();
    schedule();
    loop_.run();
    link_.link->close(std::chrono::milliseconds(200));
    return exit_code_;
  }

 private:
  void schedule() {
    timer_.expires_after(kTick);
    timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      tick();
      if (!done_) schedule();
    });
  }

  void on_frame(const mavlink::FrameView& frame, core::HostTime t) {
    const auto message = mavlink::decode_message(frame);
    if (!message) return;
    const core::ReceivedMessage received{frame.sysid, frame.compid, *message};
    (void)state_.on_message(received, t, nullptr);
    std::vector<std::string> notes;
    setup_.on_message(received, t, notes);
  }

  /// Our HEARTBEAT when due (1 Hz: a vehicle that serves UDP learns where to answer from it,
  /// as from any ground station) and `messages`, with the vehicle's identity and signing.
  void send(const std::vector<mavlink::Message>& messages, core::HostTime now) {
    // A signed link's timestamps: 10 µs units since 2015-01-01 (mavlink-wire.md §7.3).
    constexpr std::int64_t kSigningEpochUs = 1'420'070'400'000'000;
    const auto signing_now = static_cast<std::uint64_t>(
        std::max<std::int64_t>(0, io::unix_now_us() - kSigningEpochUs) / 10);
    std::vector<core::OutgoingMessage> out;
    sender_.on_tick(now, signing_now, nullptr, false,
                    out);  // HEARTBEAT only: no origin, no TIMESYNC
    for (const auto& m : messages) sender_.send(m, now, signing_now, out);
    for (const auto& o : out) (void)link_.link->send(o.frame.bytes());
  }

  web::VehicleView view(core::HostTime now) const {
    core::VehicleStatus status;
    status.name = vehicle_.spec.name;
    status.profile = vehicle_.spec.profile;
    status.vehicle = state_.snapshot();
    status.setup = setup_.snapshot();
    web::VehicleView v;
    v.name = vehicle_.spec.name;
    web::fill_setup_view(status, now, v);
    return v;
  }

  void finish(int code, const std::string& message) {
    if (!message.empty()) std::fprintf(stderr, "mocaplink vehicle setup: %s\n", message.c_str());
    exit_code_ = code;
    done_ = true;
    loop_.stop();
  }

  void tick() {
    const core::HostTime now = io::host_now();
    (void)state_.on_tick(now);
    const core::VehicleSnapshot heard = state_.snapshot();
    core::SetupTarget target;
    target.alive = heard.link == core::HeartbeatState::alive;
    if (heard.heartbeat) {
      target.autopilot = heard.heartbeat->autopilot;
      target.compid = heard.heartbeat->compid;
      target.armed = heard.heartbeat->armed;
    }
    std::vector<mavlink::Message> out;
    std::vector<std::string> notes;
    setup_.on_tick(now, target, core::DelayInputs{}, out, notes);
    send(out, now);
    const core::SetupState s = setup_.state();
    const bool listed = s == core::SetupState::ready || s == core::SetupState::blocked;
    const bool timed_out = core::to_seconds(now - started_) > options_.timeout_s;
    if (!listed) {
      if (s == core::SetupState::no_answer || s == core::SetupState::unsupported ||
          (timed_out && s != core::SetupState::waiting)) {
        report(now);
        finish(2, s == core::SetupState::unsupported
                      ? "no set-up rules for this autopilot (only PX4 and ArduPilot)"
                      : "the vehicle answered no parameter read");
      } else if (timed_out) {
        const std::string url = link_.link->url();
        // PX4 sends to the first address that spoke to its UDP port since it booted (seen with
        // PX4 1.14 SITL: a second process on the same boot heard nothing).
        finish(2, "no HEARTBEAT from the vehicle within " + format_value(options_.timeout_s) +
                      " s on " + url +
                      (url.rfind("udp://", 0) == 0
                           ? " (a PX4 answers only the first address that spoke to its UDP port "
                             "since it booted: if another program or mocaplink process did, "
                             "restart the vehicle or stop that one)"
                           : std::string()));
      }
      return;
    }
    if (options_.apply && !applied_) {
      applied_ = true;
      const web::VehicleView v = view(now);
      std::vector<std::string> names;
      for (const auto& i : v.setup.items) {
        if (i.status == "wrong" && i.fix) names.push_back(i.parameter);
      }
      report(now);  // what will be written, as it stands
      if (names.empty()) {
        finish(s == core::SetupState::blocked ? 3 : 0, "");
        return;
      }
      const core::SetupRequestResult r = setup_.apply(names, now);
      std::fprintf(stderr, "mocaplink vehicle setup: %s\n", r.message.c_str());
      if (!r.accepted) finish(3, "");
      return;
    }
    if (applied_) {
      const web::VehicleView v = view(now);
      for (const auto& i : v.setup.items) {
        if (i.apply == "pending") return;  // writes still going
      }
      report(now);
      bool failed = false;
      for (const auto& i : v.setup.items) failed = failed || i.apply == "failed";
      finish(s == core::SetupState::blocked || failed ? 3 : 0, "");
      return;
    }
    report(now);
    finish(s == core::SetupState::blocked ? 3 : 0, "");
  }

  void report(core::HostTime now) const {
    const web::VehicleView v = view(now);
    if (options_.json) {
      print_json(v);
    } else {
      print_text(v);
    }
  }

  const Options& options_;
  const config::Vehicle& vehicle_;
  asio::io_context loop_;
  core::VehicleState state_;
  core::VehicleSetup setup_;
  core::Sender sender_;
  asio::steady_timer timer_;
  VehicleLink link_;
  core::HostTime started_{};
  bool applied_ = false;
  bool done_ = false;
  int exit_code_ = 2;
};

int run_vehicle_setup(const Options& options, const sources::SourceRegistry& sources) {
  std::ifstream in(options.config_path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "mocaplink vehicle setup: cannot read %s\n", options.config_path.c_str());
    return 1;
  }
  std::stringstream text;
  text << in.rdbuf();
  const auto result = config::parse_config(text.str(), options.config_path, sources.validator());
  for (const auto& e : result.errors) std::fprintf(stderr, "%s\n", config::to_string(e).c_str());
  if (!result.ok()) return 1;
  const config::Config& cfg = *result.config;
  for (const auto& v : cfg.vehicles) {
    if (v.spec.name != options.name) continue;
    SetupSession session(v, options);
    return session.run();
  }
  std::string names;
  for (const auto& v : cfg.vehicles) names += (names.empty() ? "" : ", ") + v.spec.name;
  std::fprintf(stderr, "mocaplink vehicle setup: no vehicle named \"%s\" in %s (vehicles: %s)\n",
               options.name.c_str(), options.config_path.c_str(), names.c_str());
  return 1;
}

}  // namespace

void add_vehicle_commands(CLI::App& app, ExitCode& exit_code,
                          const sources::SourceRegistry& sources) {
  auto* vehicle = app.add_subcommand("vehicle", "A vehicle's own set-up: read it, fix it");
  vehicle->require_subcommand(1);
  const auto opts = std::make_shared<Options>();
  auto* setup = vehicle->add_subcommand(
      "setup",
      "Read the parameters the vehicle's profile depends on and list what is wrong "
      "(exit 0: nothing blocks, 2: no answer, 3: something blocks)");
  setup->add_option("--config", opts->config_path, "the run configuration (TOML)")->required();
  setup->add_option("NAME", opts->name, "the [[vehicle]] name")->required();
  setup->add_flag("--apply", opts->apply,
                  "write the fixes of the wrong items listed (never to an armed vehicle)");
  setup->add_flag("--json", opts->json, "print the fields of GET /api/vehicles/NAME instead");
  setup->add_option("--timeout", opts->timeout_s, "seconds to wait for the vehicle")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 600.0));
  setup->callback(
      [&exit_code, opts, &sources] { exit_code.value = run_vehicle_setup(*opts, sources); });
}

}  // namespace mocaplink::app

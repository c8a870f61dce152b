// `mocaplink vehicle setup --config FILE NAME [--apply] [--json] [--timeout S]` (issue 28;
// docs/setup.md): reads the vehicle's set-up list as `run` does (core::VehicleSetup) and prints
// it; with --apply writes the fixes of the wrong items it printed, never to an armed vehicle, and
// prints the list again.
//
// Who talks to the vehicle: when the configuration's dashboard answers (`mocaplink run` with this
// configuration owns the vehicle's link), the list is read and the fixes are applied through it —
// GET /api/vehicles/NAME, POST /api/vehicles/NAME/setup (docs/api.md) — and the link is never
// opened a second time. Otherwise the command opens the link itself; then nothing else is sent but
// a 1 Hz HEARTBEAT (as the vehicle's component 197, so that a vehicle serving UDP learns where to
// answer): no pose, no TIMESYNC, no origin (an ArduPilot takes an origin once per boot: only
// `run` sets it).
//
// Exit codes: 0 nothing blocks; 1 bad command line or configuration; 2 the vehicle was not heard,
// or answered no parameter read, within --timeout (or the dashboard that answered has no such
// vehicle); 3 something blocks (or a write failed).
#include <algorithm>
#include <asio/io_context.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
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
#include "mocaplink/web/dashboard_client.hpp"
#include "mocaplink/web/status_json.hpp"
#include "run_links.hpp"

namespace mocaplink::app {
namespace {

struct Options {
  std::string config_path;
  std::string name;
  bool apply = false;
  bool json = false;
  double timeout_s = 30.0;
};

/// The list as text, from the fields of GET /api/vehicles/NAME (docs/api.md): one line per item,
/// the words of the vehicle, the delay.
void print_text(const nlohmann::json& v) {
  const auto text = [](const nlohmann::json& j, const char* key) {
    return j.contains(key) && j.at(key).is_string() ? j.at(key).get<std::string>() : std::string();
  };
  const auto number = [](const nlohmann::json& j, const char* key) {
    if (!j.contains(key) || !j.at(key).is_number()) return std::string("-");
    std::ostringstream out;
    out << j.at(key).get<double>();
    return out.str();
  };
  const nlohmann::json& autopilot = v.at("autopilot");
  const nlohmann::json& setup = v.at("setup");
  const std::string version = text(autopilot, "version");
  std::printf("vehicle %s: %s%s, set-up %s\n", text(v, "name").c_str(),
              text(autopilot, "name").c_str(), version.empty() ? "" : (" " + version).c_str(),
              text(setup, "state").c_str());
  for (const nlohmann::json& i : setup.at("items")) {
    const std::string status = text(i, "status");
    const std::string apply = text(i, "apply");
    const std::string note = text(i, "apply_note");
    std::printf(
        "  %-9s %-16s now %-6s needed %s%s\n",
        (status == "ok" ? status : text(i, "severity")).c_str(), text(i, "parameter").c_str(),
        number(i, "current").c_str(), text(i, "needed").c_str(),
        apply != "none" ? (" [" + apply + (note.empty() ? "" : ": ") + note + "]").c_str() : "");
    if (status != "ok") {
      const bool reboot = i.value("reboot", false);
      std::printf("            %s%s\n", text(i, "why").c_str(), reboot ? " (after a reboot)" : "");
    }
  }
  const nlohmann::json& delay = v.at("delay_ms");
  if (!text(delay, "parameter").empty() && number(delay, "recommended") != "-") {
    std::printf("  delay: %s recommended %s ms (%s)\n", text(delay, "parameter").c_str(),
                number(delay, "recommended").c_str(), text(delay, "basis").c_str());
  }
  // The pre-flight check where it has a verdict (mocap is known only to `run`: through its
  // dashboard), with the config lines that make mocap agree with the vehicle at rest.
  const nlohmann::json& agreement = v.at("agreement");
  const std::string verdict = text(agreement, "verdict");
  if (verdict == "agree" || verdict == "disagree") {
    const auto fixed = [&](const char* key, int digits) {
      if (!agreement.contains(key) || !agreement.at(key).is_number()) return std::string("-");
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.*f", digits, agreement.at(key).get<double>());
      return std::string(buffer);
    };
    // The compass (RAW_IMU, HIGHRES_IMU) where the vehicle's yaw is mocap's and it has one.
    const std::string compass = fixed("heading_offset_deg", 1);
    // An agreement names what it rests on: "agree on tilt only" when yaw and position are
    // mocap's own (the reason below says so), so it never reads as a nose check it was not.
    std::string checked;
    if (agreement.contains("checked") && agreement.at("checked").is_array()) {
      const auto& list = agreement.at("checked");
      for (std::size_t k = 0; k < list.size(); ++k) {
        checked += (k == 0                 ? ""
                    : k + 1 == list.size() ? " and "
                                           : ", ") +
                   list[k].get<std::string>();
      }
      if (list.size() == 1) checked += " only";
    }
    const std::string headline =
        verdict == "agree" && !checked.empty() ? "agree on " + checked : verdict;
    std::printf("  agreement: %s (tilt %s deg, yaw %s deg, position %s m%s)\n", headline.c_str(),
                fixed("tilt_offset_deg", 1).c_str(), fixed("yaw_offset_deg", 1).c_str(),
                fixed("position_offset_m", 3).c_str(),
                compass == "-" ? "" : (", compass " + compass + " deg").c_str());
    // The fix in its own words (the lines, the residuals, an equally good alternative, or why
    // none fits), then what the check could not measure: the reason without the fix it starts
    // with, so the fix is printed once.
    const nlohmann::json& fix = agreement.at("fix");
    std::string reason = text(agreement, "reason");
    if (fix.is_object()) {
      const std::string fix_text = text(fix, "text");
      std::printf("    %s\n", fix_text.c_str());
      if (reason.starts_with(fix_text)) reason = reason.substr(fix_text.size());
      if (reason.starts_with("; ")) reason = reason.substr(2);
    }
    if (!reason.empty()) std::printf("            %s\n", reason.c_str());
  }
  const nlohmann::json& estimator = v.at("estimator");
  if (estimator.is_object() && !estimator.at("problems").empty()) {
    std::string problems;
    for (const auto& p : estimator.at("problems")) {
      problems += (problems.empty() ? "" : ", ") + p.get<std::string>();
    }
    std::printf("  estimator (%s): %s\n", text(estimator, "source").c_str(), problems.c_str());
  }
  for (const nlohmann::json& t : v.at("statustext")) {
    std::printf("  vehicle says (%s): %s\n", text(t, "severity").c_str(), text(t, "text").c_str());
  }
  if (!setup.at("reboot_for").empty()) {
    std::string names;
    for (const auto& n : setup.at("reboot_for")) {
      names += (names.empty() ? "" : ", ") + n.get<std::string>();
    }
    std::printf("  reboot the vehicle for %s to take effect\n", names.c_str());
  }
}

/// The fields of GET /api/vehicles/NAME that describe the set-up (docs/api.md), as one document;
/// after --apply also `applied`, the parameters written.
void print_json(const nlohmann::json& all, const std::vector<std::string>* applied) {
  nlohmann::json out;
  out["name"] = all.at("name");
  for (const char* key : {"autopilot", "setup", "statustext", "estimator", "delay_ms"}) {
    out[key] = all.at(key);
  }
  if (applied != nullptr) out["applied"] = *applied;
  std::printf("%s\n", out.dump(2).c_str());
}

struct ApplyAnswer {
  bool accepted = false;
  std::string message;  ///< what will be written, or why not
};

/// What the command talks to: the vehicle over its own link (LinkPeer), or `mocaplink run`
/// through its dashboard (DaemonPeer). Both give the vehicle as GET /api/vehicles/NAME shows it.
class SetupPeer {
 public:
  virtual ~SetupPeer() = default;
  /// Lets about one tick pass; returns the vehicle's view, or nullopt with `error` (exit 2).
  virtual std::optional<nlohmann::json> step(std::string& error) = 0;
  virtual ApplyAnswer apply(const std::vector<std::string>& names) = 0;
  /// Why the vehicle has not been heard, after `timeout_s`.
  [[nodiscard]] virtual std::string unheard(double timeout_s) const = 0;
};

/// The flow both peers share: wait for the list, print it, apply, wait for the writes, print.
class SetupFlow {
 public:
  SetupFlow(SetupPeer& peer, const Options& options) : peer_(peer), options_(options) {}

  int run() {
    const auto started = std::chrono::steady_clock::now();
    std::optional<std::chrono::steady_clock::time_point> applied_at;
    while (true) {
      std::string error;
      const auto v = peer_.step(error);
      if (!v) return fail(2, error);
      const std::string state = v->at("setup").at("state").get<std::string>();
      const bool listed = state == "ready" || state == "blocked";
      const auto now = std::chrono::steady_clock::now();
      const bool timed_out =
          std::chrono::duration<double>(now - (applied_at ? *applied_at : started)).count() >
          options_.timeout_s;
      if (!applied_at && !listed) {
        if (state == "no answer" || state == "unsupported" || (timed_out && state != "waiting")) {
          report(*v);
          return fail(2, state == "unsupported"
                             ? "no set-up rules for this autopilot (only PX4 and ArduPilot)"
                             : "the vehicle answered no parameter read");
        }
        if (timed_out) return fail(2, peer_.unheard(options_.timeout_s));
        continue;
      }
      if (!options_.apply) {
        report(*v);
        return state == "blocked" ? 3 : 0;
      }
      if (!applied_at) {
        for (const auto& i : v->at("setup").at("items")) {
          if (i.at("status") == "wrong" && !i.at("fix").is_null()) {
            names_.push_back(i.at("parameter").get<std::string>());
          }
        }
        if (!options_.json) print_text(*v);  // what will be written, as it stands
        if (names_.empty()) {
          if (options_.json) print_json(*v, &names_);
          return state == "blocked" ? 3 : 0;
        }
        const ApplyAnswer r = peer_.apply(names_);
        std::fprintf(stderr, "mocaplink vehicle setup: %s\n", r.message.c_str());
        if (!r.accepted) {
          if (options_.json) print_json(*v, nullptr);
          return 3;
        }
        applied_at = now;
        continue;
      }
      bool failed = false;
      bool pending = false;
      for (const auto& i : v->at("setup").at("items")) {
        const bool named = std::find(names_.begin(), names_.end(),
                                     i.at("parameter").get<std::string>()) != names_.end();
        const std::string apply = i.at("apply").get<std::string>();
        pending = pending || (named && (apply == "pending" || apply == "none"));
        failed = failed || apply == "failed";
      }
      if (pending && !timed_out) continue;  // writes still going
      report(*v);
      if (pending) return fail(3, "the writes were not confirmed within the timeout");
      return state == "blocked" || failed ? 3 : 0;
    }
  }

 private:
  void report(const nlohmann::json& v) const {
    if (options_.json) {
      print_json(v, options_.apply ? &names_ : nullptr);
    } else {
      print_text(v);
    }
  }

  static int fail(int code, const std::string& message) {
    if (!message.empty()) std::fprintf(stderr, "mocaplink vehicle setup: %s\n", message.c_str());
    return code;
  }

  SetupPeer& peer_;
  const Options& options_;
  std::vector<std::string> names_;  // the fixes asked for
};

/// The vehicle over the link the configuration names, opened by this process.
class LinkPeer final : public SetupPeer {
 public:
  explicit LinkPeer(const config::Vehicle& vehicle)
      : vehicle_(vehicle),
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
        }()) {
    link_ = make_vehicle_link(loop_, vehicle_);
    link_.link->start(
        [this](const mavlink::FrameView& frame, core::HostTime t) { on_frame(frame, t); },
        [this](io::TransportState state, const std::string& detail) {
          link_detail_ = std::string(io::to_string(state)) + ": " + detail;
        });
  }
  ~LinkPeer() override {
    link_.link->close(std::chrono::milliseconds(200));
    loop_.run_for(std::chrono::milliseconds(200));  // the linger: queued frames leave
  }
  LinkPeer(const LinkPeer&) = delete;
  LinkPeer& operator=(const LinkPeer&) = delete;

  std::optional<nlohmann::json> step(std::string& /*error*/) override {
    loop_.run_for(kTick);
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
    return nlohmann::json(view(now));
  }

  ApplyAnswer apply(const std::vector<std::string>& names) override {
    const core::SetupRequestResult r = setup_.apply(names, io::host_now());
    return {r.accepted, r.message};
  }

  [[nodiscard]] std::string unheard(double timeout_s) const override {
    const std::string url = link_.link->url();
    std::ostringstream seconds;
    seconds << timeout_s;
    // PX4 sends to the first address that spoke to its UDP port since it booted (seen with PX4
    // 1.14 SITL: a second process on the same boot heard nothing), unless every process speaks
    // from the same address (docs/config.md "Links").
    const bool plain_udp = vehicle_.link.kind == config::LinkKind::udp && !vehicle_.link.bind;
    const bool listening = vehicle_.link.kind == config::LinkKind::udpin;
    return "no HEARTBEAT from the vehicle within " + seconds.str() + " s on " + url +
           (link_detail_.empty() ? "" : " (link " + link_detail_ + ")") +
           (plain_udp   ? "; a PX4 answers only the first address that spoke to its UDP port since "
                          "it booted: if another program or mocaplink process did, restart the "
                          "vehicle, or give the link a fixed local port (?bind=) or listen with "
                          "udpin:// so that every mocaplink process is heard (docs/config.md)"
            : listening ? "; nothing spoke to it here: a PX4 sends its onboard link elsewhere once "
                          "another program has spoken to its port since it booted (restart the "
                          "vehicle; docs/config.md)"
                        : "");
  }

 private:
  static constexpr auto kTick = std::chrono::milliseconds(100);

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

  const config::Vehicle& vehicle_;
  asio::io_context loop_;
  core::VehicleState state_;
  core::VehicleSetup setup_;
  core::Sender sender_;
  VehicleLink link_;
  std::string link_detail_;  // the link's last state and why
};

/// `mocaplink run` with this configuration, through its dashboard: it owns the vehicle's link.
class DaemonPeer final : public SetupPeer {
 public:
  DaemonPeer(web::DashboardClient& client, std::string name)
      : client_(client), path_("/api/vehicles/" + std::move(name)) {}

  std::optional<nlohmann::json> step(std::string& error) override {
    std::this_thread::sleep_for(kPoll);
    auto answer = client_.get(path_, error);
    if (!answer) {
      error = "the dashboard at " + client_.address() + " stopped answering: " + error;
      return std::nullopt;
    }
    if (answer->status != 200) {
      error = "the dashboard at " + client_.address() + " answered GET " + path_ + " with " +
              std::to_string(answer->status) + ": " + error_text(answer->body);
      return std::nullopt;
    }
    last_ = nlohmann::json::parse(answer->body, nullptr, false);
    if (last_.is_discarded() || !last_.is_object() || !last_.contains("setup")) {
      error = "the dashboard at " + client_.address() + " answered GET " + path_ +
              " with something that is not a vehicle";
      return std::nullopt;
    }
    return last_;
  }

  ApplyAnswer apply(const std::vector<std::string>& names) override {
    std::string error;
    const nlohmann::json body = {{"apply", names}};
    const auto answer = client_.post_json(path_ + "/setup", body.dump(), error);
    if (!answer) return {false, "the dashboard at " + client_.address() + ": " + error};
    if (answer->status != 200) {
      return {false, "mocaplink run refused the writes (" + std::to_string(answer->status) +
                         "): " + error_text(answer->body)};
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return {true, "mocaplink run writes " + list};
  }

  [[nodiscard]] std::string unheard(double timeout_s) const override {
    std::ostringstream seconds;
    seconds << timeout_s;
    const auto text = [this](const char* key) {
      return last_.contains(key) && last_.at(key).is_string() ? last_.at(key).get<std::string>()
                                                              : std::string("?");
    };
    return "mocaplink run has not heard the vehicle within " + seconds.str() + " s on " +
           text("link") + " (link " + text("link_state") + ")";
  }

  /// The error text of a JSON error answer (docs/api.md "Errors"), or the body itself.
  static std::string error_text(const std::string& body) {
    const auto j = nlohmann::json::parse(body, nullptr, false);
    if (j.is_object() && j.contains("error") && j.at("error").is_string()) {
      return j.at("error").get<std::string>();
    }
    return body.substr(0, 200);
  }

 private:
  static constexpr auto kPoll = std::chrono::milliseconds(200);
  web::DashboardClient& client_;
  std::string path_;
  nlohmann::json last_;
};

/// Through `mocaplink run` when the configuration's dashboard answers for this vehicle; nullopt
/// when nothing answers there (then this process opens the link itself).
std::optional<int> setup_through_daemon(const config::Config& cfg, const config::Vehicle& vehicle,
                                        const Options& options) {
  web::DashboardClient client(cfg.http, std::chrono::milliseconds(2000));
  std::string error;
  const std::string path = "/api/vehicles/" + vehicle.spec.name;
  const auto answer = client.get(path, error);
  if (!answer) return std::nullopt;  // no daemon: open the link here
  if (answer->status != 200) {
    std::fprintf(stderr,
                 "mocaplink vehicle setup: the dashboard at %s (mocaplink run, by this "
                 "configuration's [http] listen) answered GET %s with %d: %s; the link is left to "
                 "it\n",
                 client.address().c_str(), path.c_str(), answer->status,
                 DaemonPeer::error_text(answer->body).c_str());
    return 2;
  }
  std::fprintf(stderr,
               "mocaplink vehicle setup: mocaplink run owns the link of %s: reading%s through its "
               "dashboard at %s\n",
               vehicle.spec.name.c_str(), options.apply ? " and applying" : "",
               client.address().c_str());
  DaemonPeer peer(client, vehicle.spec.name);
  try {
    return SetupFlow(peer, options).run();
  } catch (const nlohmann::json::exception& e) {
    // Another program on that port, or another version's answer: said, never a crash.
    std::fprintf(stderr,
                 "mocaplink vehicle setup: the dashboard at %s answered GET %s with a vehicle "
                 "this version cannot read (%s)\n",
                 client.address().c_str(), path.c_str(), e.what());
    return 2;
  }
}

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
    if (v.link.kind == config::LinkKind::ros2) {
      // PX4's uXRCE-DDS topics carry no parameters (docs/ros2.md "PX4 over uXRCE-DDS").
      std::fprintf(stderr,
                   "mocaplink vehicle setup: vehicle \"%s\" is reached by %s (PX4's uXRCE-DDS "
                   "topics), which carry no parameters, so its set-up list cannot be read: run "
                   "the set-up over a MAVLink link to the same PX4 (a copy of the config with "
                   "link = \"udp://...\" or \"serial://...\"; docs/setup.md)\n",
                   v.spec.name.c_str(), config::to_string(v.link).c_str());
      return 2;
    }
    if (const auto code = setup_through_daemon(cfg, v, options)) return *code;
    LinkPeer peer(v);
    return SetupFlow(peer, options).run();
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
  setup->add_flag("--json", opts->json,
                  "print the fields of GET /api/vehicles/NAME instead, as one JSON document");
  setup->add_option("--timeout", opts->timeout_s, "seconds to wait for the vehicle")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 600.0));
  setup->callback(
      [&exit_code, opts, &sources] { exit_code.value = run_vehicle_setup(*opts, sources); });
}

}  // namespace mocaplink::app

// RunDashboard (run_dashboard.hpp): the daemon side of the dashboard. HTTP threads post each
// request to the event loop and wait for its answer (bounded), so the Bridge is only ever touched
// by the loop thread, and a slow or stopping loop cannot hang the HTTP server.
#include "run_dashboard.hpp"

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>

#include <spdlog/spdlog.h>
#include <asio/post.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/web/bridge_views.hpp"
#include "mocaplink/web/dashboard_server.hpp"

namespace mocaplink::app {
namespace {

/// How long an HTTP thread waits for the loop before answering 503 / the last status.
constexpr auto kLoopTimeout = std::chrono::seconds(1);

}  // namespace

class RunDashboard::Backend final : public web::DashboardBackend {
 public:
  Backend(asio::io_context& loop, DashboardAccess access)
      : loop_(loop), access_(std::move(access)), builder_(io::host_now()) {
    context_.source = access_.config.mocap.source.text;
  }

  web::StatusView status() override {
    auto answer = on_loop<web::StatusView>([this] { return build_status(); });
    std::lock_guard lock(last_mutex_);
    if (answer) last_status_ = *answer;
    return last_status_;  // the loop did not answer in time: the previous picture
  }

  std::optional<web::ApiError> apply(const web::VehicleChange& change) override {
    auto answer =
        on_loop<std::optional<web::ApiError>>([this, change] { return apply_on_loop(change); });
    if (!answer) return web::ApiError{503, "the daemon did not answer in time; try again", ""};
    return *answer;
  }

  void stop() { stopping_ = true; }

 private:
  // Runs `f` on the loop and waits up to kLoopTimeout; std::nullopt on timeout or when stopping.
  // A call that timed out never runs later: the caller was told it did not happen (503), so a
  // change applied behind its back would make a retry fail (409/404).
  template <typename T, typename F>
  std::optional<T> on_loop(F f) {
    if (stopping_) return std::nullopt;
    enum : int { kPending, kRunning, kAbandoned };
    auto promise = std::make_shared<std::promise<T>>();
    auto phase = std::make_shared<std::atomic<int>>(kPending);
    auto future = promise->get_future();
    asio::post(loop_, [promise, phase, f = std::move(f)]() mutable {
      int expected = kPending;
      if (!phase->compare_exchange_strong(expected, kRunning)) return;  // abandoned
      promise->set_value(f());
    });
    if (future.wait_for(kLoopTimeout) == std::future_status::ready) return future.get();
    int expected = kPending;
    if (phase->compare_exchange_strong(expected, kAbandoned)) return std::nullopt;
    return future.get();  // it started just now: its answer is moments away
  }

  web::StatusView build_status() {
    // The context lists links in the snapshot's vehicle order (live vehicles by slot).
    const core::BridgeSnapshot snapshot = access_.bridge.snapshot(io::host_now());
    context_.source_error = access_.source_error;
    context_.source_rejected_reason = access_.source_counters.last_rejection.get();  // first
    context_.source_rejected = access_.source_counters.rejected();
    context_.bridge_latency = access_.bridge_latency.summary();
    context_.late_frames_skipped = access_.late_frames.skipped();
    context_.superseded_frames = access_.late_frames.superseded();
    context_.links.clear();
    context_.links_down.clear();
    context_.gcs.clear();
    context_.link_share.clear();
    context_.link_clocks.clear();
    for (const auto& v : snapshot.vehicles) {
      const io::Link* link =
          v.index < access_.vehicles.size() ? access_.vehicles[v.index].link.get() : nullptr;
      context_.links.push_back(link != nullptr ? link->url() : "");
      context_.gcs.push_back(access_.ground_stations.views(v.index));
      context_.link_share.push_back(link != nullptr ? access_.ground_stations.share(v.index, *link)
                                                    : web::LinkShareView{});
      if (const auto clock = link != nullptr ? link->clock() : std::nullopt) {
        context_.link_clocks.emplace_back(web::LinkClockView{clock->pose_stamps, clock->text});
      } else {
        context_.link_clocks.emplace_back(std::nullopt);
      }
      const auto state = link != nullptr ? link->state() : io::TransportState::closed;
      context_.links_down.push_back(state == io::TransportState::down ||
                                    state == io::TransportState::closed);
    }
    web::StatusView status = builder_.build(snapshot, context_);
    if (access_.ros2 != nullptr && access_.config.ros2) status.ros2 = ros2_view();
    if (status.ros2 && !status.ros2->error.empty()) {
      status.alerts.push_back(
          {web::AlertLevel::error, "ros2_failing", "ros2", "ROS 2: " + status.ros2->error});
    }
    return status;
  }

  web::Ros2View ros2_view() const {
    const ros2::Ros2Status s = access_.ros2->status();
    const config::Ros2Settings& settings = *access_.config.ros2;
    web::Ros2View v;
    v.running = s.running;
    v.error = s.error;
    v.domain_id = s.domain_id;
    v.network_interface = s.network_interface;
    v.ns = settings.ns;
    v.frame_id = settings.frame_id;
    v.axes = std::string(core::to_string(settings.axes));
    v.implementation = s.implementation;
    for (const auto& t : s.topics) v.topics.push_back({t.name, t.type, t.subscribers, t.published});
    v.frames_published = s.frames_published;
    v.frames_dropped = s.frames_dropped;
    v.write_errors = s.write_errors;
    v.unnamed = s.unnamed;
    v.clashes = s.clashes;
    return v;
  }

  std::optional<web::ApiError> apply_on_loop(const web::VehicleChange& change) {
    if (const auto* update = std::get_if<web::UpdateVehicle>(&change)) {
      return access_.update_vehicle(*update);
    }
    if (const auto* remove = std::get_if<web::RemoveVehicle>(&change)) {
      return access_.remove_vehicle(remove->name);
    }
    if (const auto* setup = std::get_if<web::SetupVehicle>(&change)) {
      return access_.setup_vehicle(*setup);
    }
    const web::AddVehicle& add = std::get<web::AddVehicle>(change);
    return access_.add_vehicle(add.keys, add.paused);
  }

  asio::io_context& loop_;
  DashboardAccess access_;
  web::BridgeStatusBuilder builder_;  // loop thread only
  web::BridgeStatusContext context_;  // loop thread only
  std::atomic<bool> stopping_{false};
  std::mutex last_mutex_;
  web::StatusView last_status_;
};

std::variant<std::unique_ptr<RunDashboard>, std::string> RunDashboard::start(
    asio::io_context& loop, DashboardAccess access) {
  std::unique_ptr<RunDashboard> dashboard(new RunDashboard());
  dashboard->backend_ = std::make_unique<Backend>(loop, access);
  web::DashboardServerConfig server_config;
  server_config.host = access.config.http.listen.host;
  server_config.port = access.config.http.listen.port;
  server_config.token = access.config.http.token;
  server_config.allowed_hosts = access.config.http.allowed_hosts;
  server_config.max_connections_per_client = access.config.http.max_connections_per_client;
  dashboard->server_ = std::make_unique<web::DashboardServer>(*dashboard->backend_, server_config);
  if (auto error = dashboard->server_->start()) return "dashboard: " + *error;
  return dashboard;
}

void RunDashboard::stop() {
  if (backend_) backend_->stop();
  if (server_) server_->stop();
}

RunDashboard::~RunDashboard() {
  stop();
}

}  // namespace mocaplink::app

// The daemon's object graph and lifecycle (run_daemon.hpp). Everything below runs on the event
// loop's thread except the Source's callbacks, which only push to the queue or post to the loop.
#include "run_daemon.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <spdlog/spdlog.h>
#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <asio/steady_timer.hpp>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/late_frames.hpp"
#include "mocaplink/io/bounded_queue.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/io/fork_join.hpp"
#include "mocaplink/io/link_udp.hpp"
#include "mocaplink/io/send_threads.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/io/signing_store.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/signing.hpp"
#include "mocaplink/ros2/publisher.hpp"
#include "mocaplink/sources/registry.hpp"
#include "run_config.hpp"
#include "run_dashboard.hpp"
#include "run_gcs.hpp"
#include "run_links.hpp"
#include "run_recorder.hpp"
#include "run_summary.hpp"

namespace mocaplink::app {
namespace {

using namespace std::chrono_literals;

/// Bridge::on_tick cadence (bridge.hpp asks for about 100 ms).
constexpr auto kTickPeriod = 100ms;
/// The vehicles a tick takes at a time before the loop looks for frames again (docs/daemon.md "The
/// tick in parts"): a part costs about 0.1 ms with its sends (1.2 µs a vehicle at 1000 vehicles,
/// docs/performance.md), where the whole tick of 1000 would hold a frame up to 1.5 ms.
constexpr std::size_t kTickPart = 100;
/// Recording files and the log are flushed this often: a crash loses at most this much.
constexpr auto kFlushPeriod = 1s;
/// Signing timestamps are persisted this often (mavlink-wire.md §7.3: at least once a minute).
constexpr auto kSigningSavePeriod = 30s;
/// How long a stop waits for stream links to write what they queued.
constexpr auto kLinger = 250ms;
/// A removed vehicle's link is closed at once and destroyed once it reports `closed` (a stream
/// link lingers up to kLinger first) and this long has passed, through asio::post so that the
/// destruction queues behind every completion its close already queued (io/link.hpp: a link
/// must outlive its handlers).
constexpr auto kRetireAfter = kLinger + 2s;
/// Frames waiting between the source thread and the loop; ~1 s at 240 Hz. Overflow drops the
/// oldest (io/bounded_queue.hpp) and is reported in the summary.
constexpr std::size_t kQueueCapacity = 256;

/// io::max_send_threads(), its warning logged.
std::size_t max_send_threads_logged() {
  std::string warning;
  const std::size_t threads = io::max_send_threads(&warning);
  if (!warning.empty()) spdlog::warn("{}", warning);
  return threads;
}

struct QueuedFrame {
  core::MocapFrame frame;
  core::HostTime received;  // when the source had it (its age, its spacing from the next)
  core::HostTime queued;    // when it was handed to the loop (how late the loop is)
};

class Daemon {
 public:
  Daemon(const DaemonSettings& settings, core::Bridge bridge,
         std::unique_ptr<sources::Source> source, std::unique_ptr<Recorder> recorder)
      : settings_(settings),
        bridge_(std::move(bridge)),
        source_(std::move(source)),
        recorder_(std::move(recorder)),
        queue_(kQueueCapacity),
        store_(settings.state_dir),
        send_pool_(max_send_threads_logged()),
        part_messages_(send_pool_.max_parts()),
        tick_timer_(loop_),
        flush_timer_(loop_),
        signing_timer_(loop_),
        summary_timer_(loop_),
        stop_timer_(loop_),
        config_(settings.config),
        summary_(config_, settings.summary_period),
        ground_stations_(loop_, [this](std::size_t slot, std::span<const std::uint8_t> frame) {
          // A ground station's frame: the vehicle's link takes it behind its own (poses first).
          if (io::Link* link = link_of(slot)) (void)link->send_forwarded(frame);
        }) {}

  int run();

 private:
  struct Retired {
    std::unique_ptr<io::Link> link;
    core::HostTime closed;
  };

  void restore_signing();
  void restore_signing(std::size_t slot, const config::Vehicle& vehicle);
  void open_links();
  void start_link(std::size_t slot);
  /// Tells the vehicle's link its pose period (the poses-first rule, io/poses_first.hpp).
  void set_pose_period(std::size_t slot, double rate_hz) {
    if (io::Link* link = link_of(slot); link != nullptr && rate_hz > 0.0) {
      link->set_pose_period(std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / rate_hz)));
    }
  }
  std::optional<web::ApiError> add_vehicle(const std::vector<config::VehicleKey>& keys,
                                           bool paused);
  std::optional<web::ApiError> remove_vehicle(const std::string& name);
  std::optional<web::ApiError> update_vehicle(const web::UpdateVehicle& update);
  std::optional<web::ApiError> setup_vehicle(const web::SetupVehicle& setup);
  void destroy_retired(core::HostTime now);
  void start_source();
  void drain();
  /// Logs the frames skipped as too late since the last such warning, when one is due
  /// (core::LateFrames::warning). Called from the tick: within kTickPeriod of the first skip, and
  /// nothing added to the per-frame path.
  void warn_late_frames(core::HostTime now);
  /// Logs the packets the source dropped unread (SourceCounters::rejected) when their count
  /// reaches 1, 10, 100, ... (a summary, not a line per packet), with the latest reason.
  void log_rejections();
  void on_frame(const core::MocapFrame& frame, core::HostTime received);
  /// Ticks the vehicles of slots [first, first + kTickPart) at `now` and sends what they have,
  /// then leaves the rest of the tick to a handler posted behind whatever the loop has waiting,
  /// so a frame that came meanwhile is sent first (Bridge::tick_vehicles).
  void tick_part(std::size_t first, core::HostTime now);
  void dispatch(const core::BridgeOutput& out);
  void publish_ros2();
  void start_ros2();
  /// The graph the ros2:// links join ([ros2]'s domain and interface); nullopt without [ros2].
  [[nodiscard]] std::optional<Ros2Graph> ros2_graph() const {
    if (!config_.ros2) return std::nullopt;
    return Ros2Graph{settings_.ros2_domain_id, config_.ros2->network_interface};
  }
  /// Sends messages[first, end) (one vehicle's run) to that vehicle's link, in batches.
  void send_run(std::span<const core::OutgoingMessage> messages);
  /// After messages went out: the recording and each signed vehicle's signing clock.
  void account(std::span<const core::OutgoingMessage> messages);
  void on_vehicle_frame(std::size_t vehicle, const mavlink::FrameView& frame, core::HostTime t);
  /// The link of the vehicle in `slot`, or nullptr for an empty or unknown slot.
  io::Link* link_of(std::size_t slot) const {
    return slot < vehicles_.size() ? vehicles_[slot].link.get() : nullptr;
  }
  void save_signing();
  void stop(const std::string& reason);
  template <typename F>
  void every(asio::steady_timer& timer, std::chrono::milliseconds period, F f);

  const DaemonSettings& settings_;
  asio::io_context loop_;
  core::Bridge bridge_;
  std::unique_ptr<sources::Source> source_;
  std::unique_ptr<Recorder> recorder_;
  io::BoundedQueue<QueuedFrame> queue_;
  std::vector<QueuedFrame> batch_;
  std::vector<Recorder::FrameFate> fates_;  // of batch_'s frames, for the recording (drain)
  io::SigningStore store_;
  std::vector<VehicleLink> vehicles_;  // by vehicle slot, as in the Bridge; empty: link == nullptr
  std::vector<Retired> retired_;       // links of removed vehicles, closed, not yet destroyed
  io::ForkJoin send_pool_;  // the threads that share a frame's vehicles (io/send_threads.hpp)
  /// Each send thread's messages of the current frame (on_frame), kept for their capacity.
  std::vector<std::vector<core::OutgoingMessage>> part_messages_;
  std::size_t most_send_threads_ = 1;  // the most send_pool_ threads used at once so far (logged)
  asio::steady_timer tick_timer_;
  asio::steady_timer flush_timer_;
  asio::steady_timer signing_timer_;
  asio::steady_timer summary_timer_;
  asio::steady_timer stop_timer_;
  // The configuration now: the file's, plus and minus the dashboard's adds and removals, with its
  // PATCHed rates (config::update_vehicle). Live-only choices (a PATCHed message set, pause) are
  // the Bridge's alone.
  config::Config config_;
  std::string source_error_;            // the source's last problem, "" when connected (dashboard)
  core::LatencyWindow bridge_latency_;  // frame received → its last datagram sent (dashboard)
  core::LateFrames late_frames_;        // frames that waited too long to be sent (drain)
  std::uint64_t next_rejection_log_ = 1;  // the source's rejected count logged next (1, 10, ...)
  core::BridgeOutput frame_output_;       // per frame, kept for its capacity
  core::BridgeOutput tick_output_;        // per tick part, kept for its capacity
  bool ticking_ = false;                  // a tick's parts are still to come (tick_part)
  Summary summary_;
  GroundStations ground_stations_;  // the vehicles' `gcs` endpoints (run_gcs.hpp)
  /// The [ros2] publisher (nullptr without [ros2]); its thread is off the pose path.
  std::unique_ptr<ros2::Publisher> ros2_;
  std::vector<core::PublishedBody> published_;  // per frame, kept for its capacity
  std::unique_ptr<RunDashboard> dashboard_;     // run_dashboard.hpp; after everything it reads
  bool stopping_ = false;
};

template <typename F>
void Daemon::every(asio::steady_timer& timer, std::chrono::milliseconds period, F f) {
  timer.expires_after(period);
  timer.async_wait([this, &timer, period, f](const std::error_code& error) {
    if (error || stopping_) return;
    f();
    every(timer, period, f);
  });
}

void Daemon::restore_signing() {
  bridge_.set_wall_clock(io::host_now(), io::unix_now_us());
  for (std::size_t slot = 0; slot < config_.vehicles.size(); ++slot) {
    restore_signing(slot, config_.vehicles[slot]);
  }
}

void Daemon::restore_signing(std::size_t slot, const config::Vehicle& vehicle) {
  // Every vehicle continues above its persisted timestamp (mavlink-wire.md §7.3): the core signs
  // at max(wall clock, last + 1), and the stored value becomes that vehicle's last.
  if (!vehicle.spec.signing_key) return;
  std::string problem;
  const auto stored = store_.load(vehicle.spec.name, &problem);
  if (!problem.empty()) spdlog::warn("signing: {}", problem);
  if (!stored) return;
  (void)bridge_.raise_signing_timestamp(slot, *stored);
  const std::uint64_t now = mavlink::signing_timestamp_from_unix_us(io::unix_now_us());
  if (*stored >= now) {
    spdlog::warn(
        "signing: vehicle {}: the stored signing timestamp is {:.3f} s ahead of the wall clock "
        "(clock stepped back?); signing continues from it",
        vehicle.spec.name, static_cast<double>(*stored - now) / 1e5);
  }
}

void Daemon::open_links() {
  const auto& vehicles = config_.vehicles;
  vehicles_.reserve(vehicles.size());
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    vehicles_.push_back(make_vehicle_link(loop_, vehicles[i], ros2_graph()));
    start_link(i);
    ground_stations_.add_vehicle(i, vehicles[i]);
  }
}

void Daemon::start_link(std::size_t slot) {
  io::Link* link = vehicles_[slot].link.get();
  set_pose_period(slot, bridge_.vehicle(slot)->rate_hz);
  link->start(
      [this, slot, link](const mavlink::FrameView& frame, core::HostTime t) {
        // The slot may hold another vehicle's link by now (removed, then added again).
        if (link_of(slot) == link) {
          on_vehicle_frame(slot, frame, t);
        }
      },
      [name = bridge_.vehicle(slot)->name](io::TransportState state, const std::string& detail) {
        if (state == io::TransportState::down) {
          spdlog::warn("vehicle {}: link {}: {}", name, io::to_string(state), detail);
        } else {
          spdlog::info("vehicle {}: link {}: {}", name, io::to_string(state), detail);
        }
      });
}

std::optional<web::ApiError> Daemon::add_vehicle(const std::vector<config::VehicleKey>& keys,
                                                 bool paused) {
  if (stopping_) return web::ApiError{503, "the daemon is stopping", ""};
  for (const auto& key : keys) {
    const auto* name = std::get_if<std::string>(&key.value);
    if (key.key == "name" && name != nullptr && bridge_.find_vehicle(*name)) {
      return web::ApiError{409, "a vehicle named \"" + *name + "\" exists", "name"};
    }
  }
  // The configuration's own checks first (unique system id per link, origin, ...), so a vehicle
  // added here is one the file could have held.
  auto checked = config::add_vehicle(config_, keys, "POST /api/vehicles");
  if (!checked.ok()) return web::refusal(checked.errors.front());
  for (const auto& w : checked.warnings) spdlog::warn("dashboard: {}", config::to_string(w));
  const config::Vehicle vehicle = checked.config->vehicles.back();
  const std::size_t slot = bridge_.next_slot();
  auto added = bridge_.add_vehicle(vehicle.spec);
  if (const auto* e = std::get_if<core::BridgeConfigError>(&added)) {
    const auto dot = e->field.rfind('.');
    return web::ApiError{422, e->field + ": " + e->message,
                         dot == std::string::npos ? e->field : e->field.substr(dot + 1)};
  }
  if (std::get<std::size_t>(added) != slot) {  // next_slot() promised it; never expected
    (void)bridge_.remove_vehicle(std::get<std::size_t>(added));
    return web::ApiError{500, "internal error: vehicle slot mismatch", ""};
  }
  if (paused) (void)bridge_.set_paused(slot, true);
  if (slot >= vehicles_.size()) vehicles_.resize(slot + 1);
  vehicles_[slot] = make_vehicle_link(loop_, vehicle, ros2_graph());
  start_link(slot);
  ground_stations_.add_vehicle(slot, vehicle);
  restore_signing(slot, vehicle);
  if (recorder_) {
    std::string problem;
    if (!recorder_->add_vehicle(slot, vehicle.spec.name, &problem)) {
      spdlog::warn("recording: vehicle {} is not recorded: {}", vehicle.spec.name, problem);
    }
  }
  config_ = std::move(*checked.config);
  spdlog::info("dashboard: vehicle {} added{}", vehicle.spec.name, paused ? " (paused)" : "");
  summary_.describe_vehicle(vehicle, *vehicles_[slot].link, io::host_now());
  return std::nullopt;
}

std::optional<web::ApiError> Daemon::remove_vehicle(const std::string& name) {
  if (stopping_) return web::ApiError{503, "the daemon is stopping", ""};
  const auto slot = bridge_.find_vehicle(name);
  if (!slot || link_of(*slot) == nullptr) {
    return web::ApiError{404, "no vehicle named \"" + name + "\"", ""};
  }
  (void)bridge_.remove_vehicle(*slot);
  VehicleLink& v = vehicles_[*slot];
  if (v.signing && v.last_signing_10us != 0) {
    std::string problem;
    if (!store_.save(name, v.last_signing_10us, &problem)) {
      spdlog::warn("signing: cannot persist the timestamp: {}", problem);
    }
  }
  v.link->close(kLinger);
  retired_.push_back(Retired{std::move(v.link), io::host_now()});
  ground_stations_.remove_vehicle(*slot);
  if (recorder_) recorder_->remove_vehicle(*slot);
  vehicles_[*slot] = VehicleLink{};
  while (!vehicles_.empty() && !vehicles_.back().link) vehicles_.pop_back();
  std::erase_if(config_.vehicles, [&](const config::Vehicle& c) { return c.spec.name == name; });
  spdlog::info("dashboard: vehicle {} removed", name);
  return std::nullopt;
}

std::optional<web::ApiError> Daemon::update_vehicle(const web::UpdateVehicle& update) {
  if (stopping_) return web::ApiError{503, "the daemon is stopping", ""};
  const auto slot = bridge_.find_vehicle(update.name);
  if (!slot) return web::ApiError{404, "no vehicle named \"" + update.name + "\"", ""};
  // Check everything first, then apply: nothing half-applied. The configuration's checks are a
  // file's (ranges, spellings, the origin GPS messages need), with its warnings.
  std::optional<double> rate;
  std::optional<core::MessageSet> messages;
  std::optional<config::Config> next;  // the configuration once the change is applied
  if (!update.keys.empty()) {
    auto checked = config::update_vehicle(config_, update.name, update.keys,
                                          "PATCH /api/vehicles/" + update.name);
    if (!checked.ok()) return web::refusal(checked.errors.front());
    for (const auto& w : checked.warnings) spdlog::warn("dashboard: {}", config::to_string(w));
    for (const auto& key : update.keys) {
      if (key.key == "rate_hz") {
        for (const auto& v : checked.config->vehicles) {
          if (v.spec.name == update.name) rate = v.spec.rate_hz;
        }
      } else if (key.key == "messages") {
        messages.emplace();  // spelled right: update_vehicle checked every name
        for (const auto& name : std::get<std::vector<std::string>>(key.value)) {
          if (const auto kind = core::parse_message_kind(name)) messages->insert(*kind);
        }
      }
    }
    next = std::move(checked.config);
  }
  // Messages first: set_messages refuses nothing the configuration accepted, and a refused rate
  // then leaves nothing applied.
  if (messages && !bridge_.set_messages(*slot, *messages)) {
    return web::ApiError{500, "internal error: the sender refused messages", "messages"};
  }
  if (rate && !bridge_.set_rate_hz(*slot, *rate)) {
    return web::ApiError{500, "internal error: the sender refused rate_hz", "rate_hz"};
  }
  if (rate) set_pose_period(*slot, *rate);
  if (next) config_ = std::move(*next);
  if (update.paused) (void)bridge_.set_paused(*slot, *update.paused);
  spdlog::info("dashboard: vehicle {}:{}{}{}", update.name,
               rate ? fmt::format(" rate_hz={}", *rate) : "",
               messages ? fmt::format(" messages=[{}]", core::to_string(*messages)) : "",
               update.paused ? fmt::format(" paused={}", *update.paused) : "");
  return std::nullopt;
}

std::optional<web::ApiError> Daemon::setup_vehicle(const web::SetupVehicle& setup) {
  const auto slot = bridge_.find_vehicle(setup.name);
  if (!slot) return web::ApiError{404, "no vehicle named \"" + setup.name + "\"", ""};
  const core::HostTime now = io::host_now();
  core::SetupRequestResult result;
  if (setup.reboot) {
    core::BridgeOutput out;
    result = bridge_.reboot_vehicle(*slot, now, out);
    dispatch(out);
  } else {
    result = bridge_.apply_setup(*slot, setup.apply, now);
  }
  if (!result.accepted) {
    spdlog::warn("dashboard: vehicle {}: set-up request refused: {}", setup.name, result.message);
    return web::ApiError{409, result.message, setup.reboot ? "reboot" : "apply"};
  }
  spdlog::info("dashboard: vehicle {}: {}", setup.name, result.message);
  return std::nullopt;
}

void Daemon::destroy_retired(core::HostTime now) {
  for (auto it = retired_.begin(); it != retired_.end();) {
    if (it->link->state() != io::TransportState::closed || now - it->closed < kRetireAfter) {
      ++it;
      continue;
    }
    // shared_ptr: asio handlers must be copyable.
    std::shared_ptr<io::Link> link(std::move(it->link));
    asio::post(loop_, [link]() mutable { link.reset(); });
    it = retired_.erase(it);
  }
}

void Daemon::start_source() {
  source_->start(
      [this](core::MocapFrame frame, core::HostTime received) {
        if (queue_.push(QueuedFrame{std::move(frame), received, io::host_now()})) {
          asio::post(loop_, [this] { drain(); });
        }
      },
      [this](sources::SourceState state, const std::string& detail) {
        asio::post(loop_, [this, state, detail] {
          if (stopping_) return;
          const bool connected = state == sources::SourceState::connected;
          bridge_.on_source_connection(connected);
          if (connected) {
            source_error_.clear();
          } else if (state == sources::SourceState::disconnected) {
            source_error_ = detail.empty() ? "disconnected" : detail;
          }
          if (state == sources::SourceState::disconnected) {
            spdlog::warn("source {}: {}{}{}", source_->url(), sources::to_string(state),
                         detail.empty() ? "" : ": ", detail);
          } else {
            spdlog::info("source {}: {}{}{}", source_->url(), sources::to_string(state),
                         detail.empty() ? "" : ": ", detail);
          }
          if (state == sources::SourceState::finished) stop("the source finished");
        });
      });
}

void Daemon::drain() {
  batch_.clear();
  queue_.drain(batch_);
  if (batch_.empty()) return;
  using Fate = Recorder::FrameFate;
  fates_.clear();
  // Behind (it took a frame that waited > 10 ms, or two frame periods below 200 Hz) or caught up
  // (its oldest frame found it idle)? From the hand-over, not the arrival: a VRPN frame is complete
  // only a settle time after its round's last report arrived (docs/sources.md), which is the
  // source's wait, not the loop's.
  for (const QueuedFrame& item : batch_) late_frames_.observe(item.frame);
  late_frames_.begin_batch(batch_.front().queued, io::host_now());
  for (std::size_t i = 0; i < batch_.size(); ++i) {
    const QueuedFrame& item = batch_[i];
    const QueuedFrame* next = i + 1 < batch_.size() ? &batch_[i + 1] : nullptr;
    auto fate = Fate::sent;
    if (next != nullptr &&
        late_frames_.skip_if_superseded(item.frame, item.received, next->frame, next->received)) {
      // Newest first (core/late_frames.hpp, issue 30): the loop is behind, and a newer frame with
      // all its bodies, which came after this one, is already waiting; only that one is worth it.
      fate = Fate::superseded;
    } else if (late_frames_.skip_if_late(
                   bridge_.frame_age(item.frame, item.received, io::host_now()))) {
      // Too old to send: the loop is behind, or the source delivered it late; go on with
      // fresher frames. Its age is judged now, right before its poses would be sent.
      fate = Fate::late;
    } else {
      on_frame(item.frame, item.received);
      bridge_latency_.add(io::host_now() - item.received);
    }
    fates_.push_back(fate);
  }
  // After the sends: the recording keeps every frame, one not sent as comments (a replay then
  // sends what we sent), and a slow write delays only the next frames, which are judged after;
  // the newest pose of a backlog never waits for the backlog's rows to be written.
  if (recorder_) {
    for (std::size_t i = 0; i < batch_.size(); ++i) {
      recorder_->on_frame(batch_[i].frame, batch_[i].received, fates_[i]);
    }
  }
  summary_.on_frames(batch_.size());
  late_frames_.end_batch(io::host_now());
}

void Daemon::log_rejections() {
  const auto& counters = source_->counters();
  std::string reason = counters.last_rejection.get();  // before the count: a source sets it first
  const std::uint64_t rejected = counters.rejected();
  if (rejected < next_rejection_log_) return;
  while (next_rejection_log_ <= rejected) next_rejection_log_ *= 10;
  spdlog::warn("source {}: {} packet{} rejected{}{}", source_->url(), rejected,
               rejected == 1 ? "" : "s", reason.empty() ? "" : ": ", reason);
}

void Daemon::warn_late_frames(core::HostTime now) {
  const auto late = late_frames_.warning(now);
  if (!late) return;
  if (late->superseded > 0) {
    spdlog::warn(
        "{} frame{} superseded by a newer one already waiting, not sent (the loop is behind: is "
        "the machine short of CPU for this many vehicles at these rates?)",
        late->superseded, late->superseded == 1 ? "" : "s");
  }
  if (late->skipped == 0) return;
  spdlog::warn(
      "{} frame{} skipped as too old to send, up to {:.0f} ms since capture (more than {} ms is "
      "too old: is the machine overloaded, or did the source deliver them late?)",
      late->skipped, late->skipped == 1 ? "" : "s",
      std::chrono::duration<double, std::milli>(late->oldest).count(),
      std::chrono::duration_cast<std::chrono::milliseconds>(core::kMaxFrameWait).count());
}

/// Calls f(run) for each run of consecutive messages to one vehicle (the core emits a vehicle's
/// messages of one step together, so each vehicle has one run per step).
template <typename F>
void for_each_run(std::span<const core::OutgoingMessage> messages, F f) {
  for (std::size_t first = 0, end = 0; first < messages.size(); first = end) {
    end = first + 1;
    while (end < messages.size() && messages[end].vehicle == messages[first].vehicle) ++end;
    f(messages.subspan(first, end - first));
  }
}

void Daemon::on_frame(const core::MocapFrame& frame, core::HostTime received) {
  bridge_.begin_frame(frame, received, frame_output_);  // capture time; no messages
  // The vehicles in chunks of kFrameChunk slots, each chunk's bodies tracked and its messages
  // built and sent at once (the first vehicles' poses leave before the other bodies' filters
  // have run and the last vehicles' messages are built). One thread takes
  // kVehiclesPerSendThread vehicles; more are spread over send_pool_'s threads, chunk i on thread
  // i mod threads, after every body has been tracked here (Bridge::emit_frame for disjoint slots,
  // and each vehicle's UDP link, are then used by one thread at a time). ForkJoin returns when
  // every thread is done, before the next frame, so each vehicle still gets its poses in capture
  // order. Links that cannot send in place (TCP, serial) are sent by this thread: at once in
  // part 0, which runs here, after the join for the others.
  // Small chunks: a vehicle waits for its chunk's trackers and messages before its own send, and
  // 4 measured no worse than 2 or 8 at 50 vehicles (docs/performance.md).
  constexpr std::size_t kFrameChunk = 4;
  const std::size_t slots = bridge_.slot_count();
  const std::size_t threads = io::send_threads_for(bridge_.vehicle_count(), send_pool_.max_parts());
  if (threads > most_send_threads_) {
    most_send_threads_ = threads;
    spdlog::info("sending from {} threads ({} vehicles; one thread per {}, at most {})", threads,
                 bridge_.vehicle_count(), io::kVehiclesPerSendThread, send_pool_.max_parts());
  }
  if (threads > 1) bridge_.track_bodies();
  send_pool_.run(threads, [&](std::size_t part) {
    auto& messages = part_messages_[part];
    messages.clear();
    for (std::size_t first = part * kFrameChunk; first < slots; first += threads * kFrameChunk) {
      const std::size_t begin = messages.size();
      bridge_.emit_frame(first, first + kFrameChunk, messages);
      for_each_run(std::span(messages).subspan(begin), [&](auto run) {
        const io::Link* link = link_of(run.front().vehicle);
        if (link != nullptr && (part == 0 || link->sends_in_place())) send_run(run);
      });
    }
  });
  for (std::size_t part = 0; part < threads; ++part) {
    if (part > 0) {
      for_each_run(part_messages_[part], [&](auto run) {
        const io::Link* link = link_of(run.front().vehicle);
        if (link != nullptr && !link->sends_in_place()) send_run(run);
      });
    }
    account(part_messages_[part]);
  }
  bridge_.end_frame(frame_output_);  // the bodies no vehicle needed; body events; Station
  for (const auto& e : frame_output_.events) summary_.on_event(e, io::host_now());
  if (ros2_) publish_ros2();
}

void Daemon::publish_ros2() {
  // After every vehicle's poses: the [ros2] bodies go to the publishing thread, which converts,
  // encodes and writes them (ros2/publisher.hpp).
  published_.clear();
  bridge_.published_bodies(published_);
  if (published_.empty()) return;
  ros2::FrameUpdate update;
  update.capture = bridge_.frame_capture();
  update.bodies.reserve(published_.size());
  for (const core::PublishedBody& b : published_) {
    update.bodies.push_back({std::string(b.name), *b.estimate, *b.axes});
  }
  ros2_->publish(std::move(update));
}

void Daemon::tick_part(std::size_t first, core::HostTime now) {
  if (stopping_) {
    ticking_ = false;
    return;
  }
  const std::size_t end = first + kTickPart;
  bridge_.tick_vehicles(now, first, end, tick_output_);
  dispatch(tick_output_);
  ticking_ = end < bridge_.slot_count();
  if (ticking_) asio::post(loop_, [this, end] { tick_part(end, io::host_now()); });
}

void Daemon::dispatch(const core::BridgeOutput& out) {
  for_each_run(out.messages, [&](auto run) { send_run(run); });
  account(out.messages);
  for (const auto& e : out.events) summary_.on_event(e, io::host_now());
}

void Daemon::send_run(std::span<const core::OutgoingMessage> run) {
  io::Link* link = link_of(run.front().vehicle);
  if (link == nullptr) return;
  std::array<std::span<const std::uint8_t>, io::UdpLink::kMaxBatch> batch;
  for (std::size_t k = 0; k < run.size();) {
    std::size_t n = 0;
    while (k < run.size() && n < batch.size()) batch[n++] = run[k++].frame.bytes();
    (void)link->send_batch({batch.data(), n});
  }
}

void Daemon::account(std::span<const core::OutgoingMessage> messages) {
  const bool recording = recorder_ != nullptr;
  const std::int64_t unix_us = recording ? io::unix_now_us() : 0;
  for (const auto& m : messages) {
    if (link_of(m.vehicle) == nullptr) continue;
    auto& v = vehicles_[m.vehicle];
    if (recording) recorder_->on_mavlink(m.vehicle, unix_us, m.frame.bytes());
    if (v.signing) {
      // The signature block of the frame we encoded (mavlink-wire.md §7.1), read by the codec.
      const auto view = mavlink::parse_frame(m.frame.bytes());
      if (view && view->signature) v.last_signing_10us = view->signature->timestamp_10us;
    }
  }
}

void Daemon::on_vehicle_frame(std::size_t vehicle, const mavlink::FrameView& frame,
                              core::HostTime t) {
  if (stopping_) return;
  if (recorder_) recorder_->on_mavlink(vehicle, io::unix_now_us(), frame.bytes);
  const VehicleLink& v = vehicles_[vehicle];
  if (v.signing && frame.is_signed()) {
    // The link verified it: our clock must stay above what the vehicle has seen (§7.3).
    (void)bridge_.raise_signing_timestamp(vehicle, v.link->verified_timestamp_10us());
  }
  // Ground stations hear the vehicle as over the direct link: every frame, unchanged, where its
  // target was heard (run_gcs.hpp). An unknown id passes too: mavlink-router forwards it.
  ground_stations_.from_vehicle(vehicle, frame);
  const auto message = mavlink::decode_message(frame);
  if (!message) return;  // unknown id: counted by the parser, nothing for the core
  dispatch(bridge_.on_vehicle_message(
      vehicle, core::ReceivedMessage{frame.sysid, frame.compid, *message}, t));
}

void Daemon::save_signing() {
  for (std::size_t slot = 0; slot < vehicles_.size(); ++slot) {
    const VehicleLink& v = vehicles_[slot];
    if (!v.link || !v.signing || v.last_signing_10us == 0) continue;
    std::string problem;
    if (!store_.save(bridge_.vehicle(slot)->name, v.last_signing_10us, &problem)) {
      spdlog::warn("signing: cannot persist the timestamp: {}", problem);
    }
  }
}

void Daemon::stop(const std::string& reason) {
  if (stopping_) return;
  spdlog::info("stopping: {}", reason);
  // 1. No more frames: join the source thread. Frames still queued are discarded, not
  //    processed: poses from them would be stale, and a loop that fell behind must not delay
  //    the stop by working through its backlog.
  source_->stop();
  stopping_ = true;
  batch_.clear();
  if (queue_.drain(batch_) > 0) spdlog::info("{} queued frames discarded", batch_.size());
  tick_timer_.cancel();
  flush_timer_.cancel();
  signing_timer_.cancel();
  summary_timer_.cancel();
  // 2. Persist, report, close files. UDP sends were synchronous, so they have left already.
  save_signing();
  summary_.flush(io::host_now(), true);  // the last word of every burst
  summary_.log(bridge_.snapshot(io::host_now()), vehicles_, queue_.overflows(),
               late_frames_.skipped(), late_frames_.superseded(), true);
  if (recorder_) {
    recorder_->close();
    const auto not_sent = recorder_->frames_not_sent();
    spdlog::info("recording: {} frames in {}{}{}", recorder_->frames_written(),
                 recorder_->dir().string(),
                 not_sent > 0 ? fmt::format(" ({} not sent, written as comments)", not_sent) : "",
                 recorder_->failed() ? " (WRITE ERRORS)" : "");
  }
  // 3. Stream links get a bounded time to write their backlog; then the loop ends.
  for (auto& v : vehicles_) {
    if (v.link) v.link->close(kLinger);
  }
  ground_stations_.close(kLinger);
  stop_timer_.expires_after(kLinger + 50ms);
  stop_timer_.async_wait([this](const std::error_code&) { loop_.stop(); });
}

void Daemon::start_ros2() {
  if (!config_.ros2) return;
  ros2::Ros2Options options;
  options.settings = *config_.ros2;
  options.domain_id = settings_.ros2_domain_id;
  options.world = bridge_.config().world;
  ros2_ = ros2::start_publisher(options);  // a participant that fails is an error in its status
}

int Daemon::run() {
  io::StopSignals signals(loop_, [this](std::string_view what, int count) {
    if (count == 1) {
      stop(std::string(what));
    } else {
      spdlog::warn("second signal: stopping now");
      loop_.stop();
    }
  });
  start_ros2();
  // The dashboard first: a bad [http] listen stops us before anything is sent.
  auto dashboard = RunDashboard::start(
      loop_,
      DashboardAccess{bridge_, config_, vehicles_, ground_stations_, source_error_,
                      source_->counters(), bridge_latency_, late_frames_,
                      [this](const std::vector<config::VehicleKey>& keys, bool paused) {
                        return add_vehicle(keys, paused);
                      },
                      [this](const std::string& name) { return remove_vehicle(name); },
                      [this](const web::UpdateVehicle& update) { return update_vehicle(update); },
                      [this](const web::SetupVehicle& setup) { return setup_vehicle(setup); },
                      ros2_.get()});
  if (const auto* error = std::get_if<std::string>(&dashboard)) {
    spdlog::error("{}", *error);
    return kExitRuntime;
  }
  dashboard_ = std::move(std::get<std::unique_ptr<RunDashboard>>(dashboard));
  restore_signing();
  open_links();
  const core::HostTime begun = io::host_now();
  for (std::size_t slot = 0; slot < vehicles_.size(); ++slot) {  // slot i: config vehicle i
    summary_.describe_vehicle(config_.vehicles[slot], *vehicles_[slot].link, begun);
  }
  summary_.begin(begun);
  start_source();
  every(tick_timer_, kTickPeriod, [this] {
    const core::HostTime now = io::host_now();
    // A ros2:// link picks its poses' stamps from PX4's own time sync: the delay follows it.
    for (std::size_t slot = 0; slot < vehicles_.size(); ++slot) {
      const io::Link* link = vehicles_[slot].link.get();
      if (const auto clock = link != nullptr ? link->clock() : std::nullopt) {
        (void)bridge_.set_capture_stamps(slot, clock->pose_stamps == core::DdsPoseStamps::capture);
      }
    }
    if (!ticking_) {  // a tick still in parts 100 ms on (a loop that far behind) goes on instead
      bridge_.begin_tick();
      tick_part(0, now);
    }
    summary_.flush(now);
    ground_stations_.on_tick(now);
    for (std::size_t slot = 0; slot < vehicles_.size(); ++slot) {
      if (vehicles_[slot].link) ground_stations_.sample(slot, *vehicles_[slot].link, now);
    }
    destroy_retired(now);
    warn_late_frames(now);
    log_rejections();
  });
  every(flush_timer_, kFlushPeriod, [this] {
    if (recorder_) recorder_->flush();
    spdlog::default_logger()->flush();  // a log file (Windows) loses at most this much
  });
  every(signing_timer_, kSigningSavePeriod, [this] { save_signing(); });
  every(summary_timer_, settings_.summary_period, [this] {
    summary_.log(bridge_.snapshot(io::host_now()), vehicles_, queue_.overflows(),
                 late_frames_.skipped(), late_frames_.superseded(), false);
  });
  dispatch(bridge_.on_tick(io::host_now()));  // first heartbeats at once
  loop_.run();
  dashboard_.reset();  // requests still waiting for the loop give up within a second
  source_->stop();     // idempotent; covers a loop stopped by a second signal
  return kExitClean;
}

}  // namespace

int run_daemon(const DaemonSettings& settings, const sources::SourceRegistry& sources) {
  std::string error;
  const auto bridge_config = make_bridge_config(settings.config, error);
  if (!bridge_config) {
    spdlog::error("configuration: {}", error);
    return kExitBadInput;
  }
  auto made = core::Bridge::make(*bridge_config, io::host_now());
  if (const auto* e = std::get_if<core::BridgeConfigError>(&made)) {
    spdlog::error("configuration: {}: {}", e->field, e->message);
    return kExitBadInput;
  }
  auto source = sources.open(settings.config.mocap.source.text);
  if (const auto* e = std::get_if<std::string>(&source)) {
    spdlog::error("source {}: {}", settings.config.mocap.source.text, *e);
    return kExitBadInput;
  }
  std::unique_ptr<Recorder> recorder;
  if (settings.record_dir) {
    std::vector<std::string> names;
    for (const auto& v : settings.config.vehicles) names.push_back(v.spec.name);
    recorder =
        Recorder::create(*settings.record_dir, settings.config.mocap.source.text, names, &error);
    if (!recorder) {
      spdlog::error("--record: {}", error);
      return kExitRuntime;
    }
    // The Bridge's rule for a restarted source (bridge.hpp): the recording follows it.
    recorder->set_restart_step_back(std::chrono::duration_cast<core::Duration>(
        std::chrono::duration<double, std::milli>(settings.config.tracking.loss_timeout_ms)));
    spdlog::info("recording to {}", settings.record_dir->string());
  }
  Daemon daemon(settings, std::move(std::get<core::Bridge>(made)),
                std::move(std::get<std::unique_ptr<sources::Source>>(source)), std::move(recorder));
  return daemon.run();
}

}  // namespace mocaplink::app
